# Standard and reverse-Z depth of the same scene describe the same geometry, so the AO must be the
# same (mean |diff| below half an 8-bit step, 0.5/255) for a scene folder (depth_reversed.pfm and
# projection_reversed) and for separate files with --fov/--near/--far (the perspective the CLI
# builds). --compare skips background pixels by the run's convention (depth 0 is the far plane in
# reverse-Z): its pixel count must equal the standard depth's foreground (depth < 1), counted
# independently by cli_tool.
include(${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake)
set(HALF_STEP 0.00196)
cacao_ok(std --scene ${ROOM} --validate -o ${WORK}/std.pfm)
cacao_ok(rev --scene ${ROOM} --validate --reverse-z -o ${WORK}/rev.pfm --compare ${WORK}/std.pfm)
mean_abs_diff(d ${WORK}/std.pfm ${WORK}/rev.pfm)
expect_between("scene folder: standard vs reverse-Z, mean |diff|" ${d} 0 ${HALF_STEP})
tool(foreground foreground ${ROOM}/depth.pfm)
if(NOT rev_out MATCHES "over ${foreground} non-background pixels")
  message(FATAL_ERROR "reverse-Z --compare should count the ${foreground} foreground pixels: ${rev_out}")
endif()

set(LENS --fov 60 --near 0.1 --far 500 --radius 0.5 --validate)
cacao_ok(std2 --depth ${ROOM}/depth.pfm ${LENS} -o ${WORK}/std2.pfm)
cacao_ok(rev2 --depth ${ROOM}/depth_reversed.pfm ${LENS} --reverse-z -o ${WORK}/rev2.pfm)
mean_abs_diff(d2 ${WORK}/std2.pfm ${WORK}/rev2.pfm)
expect_between("--fov/--near/--far: standard vs reverse-Z, mean |diff|" ${d2} 0 ${HALF_STEP})
