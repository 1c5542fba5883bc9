# "Values are literal" holds at the float limits (issue 35, defect 6). The settings are IEEE-754
# binary32 floats: nonzero values from 2^-126 = 1.17549435e-38 (FLT_MIN; below it only denormals,
# then 0) to 3.40282347e+38 (FLT_MAX). A literal is checked as the double it was parsed to, so:
#   - a nonzero value below FLT_MIN is refused: it used to become 0, which the settings read as
#     "the default" (--radius 1e-50 ran with 1.2, --horizon 1e-50 with 0.06) or a denormal
#     (--thickness 1e-45 made the AO all white); 0 itself keeps its literal meaning;
#   - a value just above FLT_MIN is kept, not replaced by the default;
#   - a value above FLT_MAX gets the setting's range message, as 200000 does, not "not a finite
#     number" (it is finite);
#   - the same holds in a --settings file, and in cacao-bench, which parses the same flags.
# Inputs: CACAO, BENCH (may be empty), WORK, SCENES.
include(${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake)
set(in --scene ${ROOM} --print-settings)

expect_cacao_refused("--radius 1e-50: too small to keep: a nonzero value must be at least 1.17549e-38" ${in}
                     --radius 1e-50)
expect_cacao_refused("--horizon 1e-50: too small to keep" ${in} --horizon 1e-50)
expect_cacao_refused("--thickness 1e-45: too small to keep" ${in} --estimator bitmask --thickness 1e-45)
expect_cacao_refused("--fade-out 1e-50,300: too small to keep" ${in} --fade-out 1e-50,300)
expect_cacao_refused("--radius 1e39: settings.radius is outside (0, 100000]" ${in} --radius 1e39)
expect_cacao_refused("--strength 1e39: settings.shadow_multiplier is outside (0, 5]" ${in} --strength 1e39)
expect_cacao_refused("--radius 200000: settings.radius = 200000 is outside (0, 100000]" ${in} --radius 200000)
file(WRITE ${WORK}/tiny.json "{\"horizon_angle_threshold\": 1e-50}")
expect_cacao_refused("tiny.json: \"horizon_angle_threshold\": too small to keep" ${in} --settings ${WORK}/tiny.json)

cacao_ok(kept ${in} --radius 1.2e-38 --horizon 0 --estimator bitmask --thickness 2e-38)
foreach(key radius horizon_angle_threshold thickness)
  string(JSON ${key} GET "${kept_out}" ${key})
endforeach()
if(radius LESS 1.19e-38 OR radius GREATER 1.21e-38 OR NOT horizon_angle_threshold EQUAL 0 OR thickness LESS 1.99e-38
   OR thickness GREATER 2.01e-38)
  message(FATAL_ERROR "values at the float limit were not kept: radius ${radius}, horizon ${horizon_angle_threshold}, "
                      "thickness ${thickness}")
endif()

if(BENCH)
  expect_program_refused(${BENCH} "--radius 1e-50: too small to keep" --configs lowest_native --radius 1e-50)
  expect_program_refused(${BENCH} "--radius 1e39: settings.radius is outside (0, 100000]" --configs lowest_native
                         --radius 1e39)
endif()
