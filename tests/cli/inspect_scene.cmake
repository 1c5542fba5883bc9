# cacao-inspect plan --scene runs one frame of a scene on the device and prints, beside the plan,
# the tile counts per class and the work each step skipped. Checked against facts known apart from
# it: the classes add up to the tile grid the plan prints; generate runs + skips = every tile, the
# fill writes at most the skipped tiles (those a later pass reads), blur runs + skips = every blur group; and the counts are
# the ones `cacao --timings --json` reports for the same frame. A horizon-slice estimator has no
# classification and says so; --size with --scene and a missing scene are refused with a message
# naming the flag. Inputs: CACAO, INSPECT, WORK, SCENES.
include(${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/../cmake/inspect_common.cmake)
function(number_after text regex var)
  if(NOT text MATCHES "${regex}")
    message(FATAL_ERROR "no match for '${regex}' in:\n${text}")
  endif()
  set(${var} "${CMAKE_MATCH_1}" PARENT_SCOPE)
endfunction()

# A fade-out inside the room, so that all three classes occur (as in test_tiles).
set(flags --quality high --fade-out 6,12 --validate)
inspect(0 plan --scene ${ROOM} ${flags})
number_after("${out}" "\ntiles: ([0-9]+)x[0-9]+ of 8x8 slice texels" gx)
number_after("${out}" "\ntiles: [0-9]+x([0-9]+) of 8x8 slice texels" gy)
number_after("${out}" "\ntiles: ([0-9]+) \\(" tiles)
number_after("${out}" ": ([0-9]+) active" active)
number_after("${out}" "active \\([0-9.]+%\\), ([0-9]+) faded" faded)
number_after("${out}" "faded \\([0-9.]+%\\), ([0-9]+) background" background)
number_after("${out}" "generate\\.q2 +runs ([0-9]+) of" gen_run)
number_after("${out}" "generate\\.q2 +runs [0-9]+ of ([0-9]+) tiles" gen_total)
number_after("${out}" "generate\\.q2 +runs [0-9]+ of [0-9]+ tiles, skips ([0-9]+)" gen_skipped)
number_after("${out}" "fill +writes AO 1 into the ([0-9]+) of the [0-9]+ skipped tiles" filled)
number_after("${out}" "fill +writes AO 1 into the [0-9]+ of the ([0-9]+) skipped tiles" fill_skipped)
number_after("${out}" "blur\\.2\\.fp32 +runs ([0-9]+) of" blur_run)
number_after("${out}" "blur\\.2\\.fp32 +runs [0-9]+ of ([0-9]+) groups" blur_total)
number_after("${out}" "blur\\.2\\.fp32 +runs [0-9]+ of [0-9]+ groups, skips ([0-9]+)" blur_skipped)
math(EXPR grid "${gx} * ${gy}")
math(EXPR classes "${active} + ${faded} + ${background}")
math(EXPR gen_sum "${gen_run} + ${gen_skipped}")
math(EXPR blur_sum "${blur_run} + ${blur_skipped}")
if(NOT tiles EQUAL grid OR NOT classes EQUAL tiles OR NOT gen_total EQUAL tiles OR NOT gen_sum EQUAL tiles OR
   filled GREATER gen_skipped OR NOT fill_skipped EQUAL gen_skipped OR NOT blur_sum EQUAL blur_total)
  message(FATAL_ERROR "the counts do not add up (grid ${gx}x${gy}, classes ${active}+${faded}+${background} of "
                      "${tiles}, generate ${gen_run}+${gen_skipped} of ${gen_total}, fill ${filled}, blur "
                      "${blur_run}+${blur_skipped} of ${blur_total}):\n${out}")
endif()
if(active EQUAL 0 OR faded EQUAL 0 OR background EQUAL 0 OR gen_skipped EQUAL 0)
  message(FATAL_ERROR "the room with a fade-out at 6..12 should have tiles of every class and skip some:\n${out}")
endif()
foreach(step prepare_depths.mips.native classify compact)
  if(NOT out MATCHES "${step} +runs over everything")
    message(FATAL_ERROR "${step} should run over everything:\n${out}")
  endif()
endforeach()
# the CPU forms without reuse: smart apply over the blocks holding a needed tile, the output of the
# skipped tiles filled; the quiet test found the room not quiet (docs/tiles.md)
number_after("${out}" "apply\\.smart_list\\.fp32 +runs over the blocks of 2x2 tiles holding one of the ([0-9]+) needed" apply_needed)
number_after("${out}" "compact +runs over everything; writes AO 1 into the output of the ([0-9]+) skipped tiles" output_filled)
if(NOT apply_needed EQUAL gen_run OR NOT output_filled EQUAL gen_skipped OR
   NOT out MATCHES "classify\\.quiet +found a pixel that can be occluded: the frame is not quiet")
  message(FATAL_ERROR "apply over its list, compact's stores of the output and the quiet test:\n${out}")
endif()

# LOWEST (the half apply): compact lists apply's groups where at most 2/3 of the tiles are active
# (docs/tiles.md "Apply over a list where the frame skips much"), the direct apply's gate closed and
# the output of the skipped tiles stored by compact; elsewhere the direct apply runs and every
# skipped tile is filled. A fade-out close to the camera makes the first, none the second.
foreach(fade "2,4" "")
  if(fade)
    inspect(0 plan --scene ${ROOM} --quality lowest --fade-out ${fade} --validate)
  else()
    inspect(0 plan --scene ${ROOM} --quality lowest --validate)
  endif()
  number_after("${out}" "\ntiles: ([0-9]+) \\(" lt)
  number_after("${out}" ": ([0-9]+) active" la)
  number_after("${out}" "generate[.a-z0-9_]* +runs [0-9]+ of [0-9]+ tiles, skips ([0-9]+)" ls)
  number_after("${out}" "fill +writes AO 1 into the ([0-9]+) of the" lf)
  math(EXPR a3 "3 * ${la}")
  math(EXPR t2 "2 * ${lt}")
  if(a3 GREATER t2)
    set(direct TRUE)
  else()
    set(direct FALSE)
  endif()
  if(fade AND direct)
    message(FATAL_ERROR "a fade-out at ${fade} should leave at most 2/3 of the tiles active:\n${out}")
  endif()
  if(direct AND (NOT out MATCHES "apply\\.half\\.fp32 +runs over everything" OR
                 NOT out MATCHES "apply\\.half_list\\.fp32 +its list is empty" OR NOT lf EQUAL ls))
    message(FATAL_ERROR "${la} of ${lt} tiles active: apply over every group, every skipped tile filled:\n${out}")
  endif()
  if(NOT direct AND (NOT out MATCHES "apply\\.half\\.fp32 +gated: at most 2/3" OR
                     NOT out MATCHES "apply\\.half_list\\.fp32 +runs over the tiles whose quads touch" OR
                     NOT out MATCHES "compact +runs over everything; writes AO 1 into the output" OR NOT lf LESS ls))
    message(FATAL_ERROR "${la} of ${lt} tiles active: apply over compact's list, fewer tiles filled:\n${out}")
  endif()
endforeach()

# The same frame through the cacao command: the same counts.
cacao_ok(run --scene ${ROOM} ${flags} --timings --repeat 1 --json ${WORK}/t.json -o ${WORK}/t.pfm)
file(READ ${WORK}/t.json report)
foreach(pair "tiles;${tiles}" "active;${active}" "faded;${faded}" "background;${background}"
             "generate_run;${gen_run}" "blur_run;${blur_run}" "blur_total;${blur_total}" "fill_run;${filled}")
  list(GET pair 0 key)
  list(GET pair 1 want)
  string(JSON got GET "${report}" tiles ${key})
  if(NOT got EQUAL want)
    message(FATAL_ERROR "tiles.${key}: cacao says ${got}, cacao-inspect ${want}\n${report}\n${out}")
  endif()
endforeach()

# The horizon estimators classify too (docs/tiles.md): their estimator and denoise steps report
# the tiles they ran; with --all-tiles every tile runs.
inspect(0 plan --scene ${ROOM} --estimator gtao)
if(NOT out MATCHES "horizon_main[.a-z_]* +runs [0-9]+ of [0-9]+ tiles" OR
   NOT out MATCHES "horizon_denoise[.a-z_]* +runs [0-9]+ of [0-9]+ tiles")
  message(FATAL_ERROR "a slice estimator's steps should report their tiles:\n${out}")
endif()
inspect(0 plan --scene ${ROOM} --estimator gtao --all-tiles)
if(NOT out MATCHES "horizon_main[.a-z_]* +runs ([0-9]+) of ([0-9]+) tiles, skips 0 ")
  message(FATAL_ERROR "--all-tiles should run every tile:\n${out}")
endif()
inspect(1 plan --scene ${ROOM} --size 64x64)
if(NOT err MATCHES "--size: not with --scene")
  message(FATAL_ERROR "--size with --scene: ${err}")
endif()
inspect(1 plan --scene ${WORK}/nowhere)
if(NOT err MATCHES "--scene ${WORK}/nowhere")
  message(FATAL_ERROR "a missing scene should be named: ${err}")
endif()
message("cacao-inspect plan --scene: counts add up and match cacao --timings")
