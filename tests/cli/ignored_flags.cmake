# A flag that would not apply is refused, never accepted and ignored (issue 35, defect 8). Each case
# gets one line naming the flag and a non-zero exit:
#   - --slices, --steps, --visibility and --frame (gtao, bitmask) and --thickness (bitmask) with an
#     estimator that does not read them: in cacao, cacao-inspect plan and, per configuration,
#     cacao-bench; with an estimator that does, they are taken (and reach the settings);
#   - cacao-bench: --estimator, --quality, --downsample, --blur, --precision (each configuration
#     sets them), run flags with --plot-from and --list-configs (which run nothing);
#   - cacao-inspect plan: the cacao command's output flags (plan writes nothing), and with --size
#     the flags of a frame (--device, --frame, --camera: plan --size runs none); plan --help prints
#     the usage;
#   - cacao-bench --configs is read whole: a list longer than 4095 characters keeps its last entry.
# Inputs: CACAO, BENCH and INSPECT (either may be empty), TOOL, WORK, SCENES.
include(${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake)

# ---- cacao ----
set(in --scene ${ROOM} --print-settings)
expect_cacao_refused("--slices: only for the gtao and bitmask estimators, and this run uses the cacao estimator" ${in}
                     --slices 4)
expect_cacao_refused("--steps: only for the gtao and bitmask estimators" ${in} --quality low --steps 4)
expect_cacao_refused("--visibility: only for the gtao and bitmask estimators" ${in} --visibility binary)
expect_cacao_refused("--frame: only for the gtao and bitmask estimators" ${in} --estimator cacao --frame 3)
expect_cacao_refused("--thickness: only for the bitmask estimator, and this run uses the gtao estimator" ${in}
                     --estimator gtao --thickness 2)
cacao_ok(taken ${in} --estimator bitmask --slices 4 --steps 5 --visibility binary --thickness 2 --frame 3)
string(JSON slices GET "${taken_out}" horizon_slices)
string(JSON thickness GET "${taken_out}" thickness)
if(NOT slices EQUAL 4 OR NOT thickness EQUAL 2)
  message(FATAL_ERROR "bitmask flags were not taken: ${taken_out}")
endif()

# ---- cacao-bench ----
if(BENCH)
  set(scene ${WORK}/s)
  file(MAKE_DIRECTORY ${scene})
  tool(ignored scene ${scene} 32 18)
  foreach(flag "--estimator;bitmask" "--quality;high" "--downsample" "--blur;3" "--precision;fp16")
    list(GET flag 0 name)
    expect_program_refused(${BENCH} "${name}: each configuration sets it" --configs lowest_native ${flag})
  endforeach()
  expect_program_refused(${BENCH} "--slices: only for the gtao and bitmask estimators, and configuration lowest_native uses the cacao estimator"
                         --configs gtao_lowest_native,lowest_native --slices 2)
  expect_program_refused(${BENCH} "--thickness: only for the bitmask estimator, and configuration gtao_lowest_native"
                         --configs gtao_lowest_native --thickness 2)
  file(WRITE ${WORK}/from.json "{}")
  expect_program_refused(${BENCH} "--repeat: not with --plot-from" --plot-from ${WORK}/from.json --plot p.png --repeat 3)
  expect_program_refused(${BENCH} "--radius: not with --plot-from" --plot-from ${WORK}/from.json --plot p.png --radius 2)
  expect_program_refused(${BENCH} "--scene: not with --plot-from" --plot-from ${WORK}/from.json --plot p.png --scene s)
  expect_program_refused(${BENCH} "--json: not with --list-configs" --list-configs --json ${WORK}/l.json)
  expect_program_refused(${BENCH} "--slices: not with --list-configs" --list-configs --configs "gtao_*" --slices 2)
  if(EXISTS ${WORK}/l.json OR EXISTS ${WORK}/p.png)
    message(FATAL_ERROR "a refused flag left a file")
  endif()
  # Taken where every configuration reads it.
  execute_process(COMMAND ${BENCH} --scene ${scene} --configs gtao_lowest_native --repeat 1 --warmup 0 --slices 2
                          --json ${WORK}/gtao.json RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
  file(READ ${WORK}/gtao.json json)
  string(JSON slices GET "${json}" results 0 settings horizon_slices)
  if(NOT rc EQUAL 0 OR NOT slices EQUAL 2)
    message(FATAL_ERROR "cacao-bench --configs gtao_lowest_native --slices 2: exit ${rc}, slices ${slices}: ${err}")
  endif()
  # --configs longer than 4095 characters: its last entry counts.
  string(REPEAT "lowest_native," 300 padding)
  execute_process(COMMAND ${BENCH} --list-configs --configs "${padding}high_native" RESULT_VARIABLE rc
                  OUTPUT_VARIABLE listed ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT listed STREQUAL "lowest_native\nhigh_native\n")
    message(FATAL_ERROR "a 4213-character --configs: exit ${rc}, listed '${listed}' ${err}")
  endif()
endif()

# ---- cacao-inspect plan ----
if(INSPECT)
  foreach(flag "-o;x.png" "--json;p.json" "--compare;gt.pfm" "--timings" "--repeat;3")
    list(GET flag 0 name)
    expect_program_refused(${INSPECT} "is a flag of the cacao command; plan prints the plan and writes nothing" plan
                           --size 64x64 ${flag})
  endforeach()
  foreach(flag "--device;0" "--frame;2" "--camera;${ROOM}/camera.json" "--reverse-z")
    list(GET flag 0 name)
    expect_program_refused(${INSPECT} "plan --size: ${name} is for a plan of --scene or --depth" plan --size 64x64
                           ${flag})
  endforeach()
  expect_program_refused(${INSPECT} "--slices: only for the gtao and bitmask estimators, and this plan uses the cacao"
                         plan --size 64x64 --slices 3)
  execute_process(COMMAND ${INSPECT} plan --size 64x64 --help RESULT_VARIABLE rc OUTPUT_VARIABLE usage)
  if(NOT rc EQUAL 0 OR NOT usage MATCHES "^usage: cacao-inspect")
    message(FATAL_ERROR "plan --help: exit ${rc}, stdout '${usage}'")
  endif()
endif()
