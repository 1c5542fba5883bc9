# --reuse (docs/tiles.md "Reusing the previous frame") through the command: the last of several
# frames of the same depth is the frame computed alone, byte for byte, and reports no tile changed;
# --move-box makes every frame after the first change some tiles and still gives the moved frame's
# own output (its last frame, the fourth, is the moved one: compared with the moved depth computed
# alone through the same flag and --repeat 1 --warmup 1, whose second frame is the moved one);
# --move-camera makes every frame a full one; a box outside the depth, and --keep-output without
# --reuse, are one clear error each and no
# output.
include(${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake)
# Fails unless the two files are byte for byte the same; <what> names the case.
function(expect_same_file what a b)
  file(SHA256 ${a} ha)
  file(SHA256 ${b} hb)
  if(NOT ha STREQUAL hb)
    message(FATAL_ERROR "${what}: ${b} differs from ${a}")
  endif()
endfunction()
# Sets <prefix>_changed and <prefix>_tiles from a --json report's tile counts.
function(reuse_counts prefix json)
  file(READ ${json} report)
  string(JSON changed GET "${report}" tiles changed)
  string(JSON tiles GET "${report}" tiles tiles)
  string(JSON recomputed GET "${report}" tiles recomputed)
  set(${prefix}_changed ${changed} PARENT_SCOPE)
  set(${prefix}_tiles ${tiles} PARENT_SCOPE)
  set(${prefix}_recomputed ${recomputed} PARENT_SCOPE)
endfunction()
cacao_ok(full --scene ${ROOM} --quality high -o ${WORK}/full.pfm)
cacao_ok(kept --scene ${ROOM} --quality high --reuse --keep-output --validate --warmup 1 --repeat 3 --timings
         --json ${WORK}/kept.json -o ${WORK}/kept.pfm)
expect_same_file("--reuse --keep-output, unchanged frames" ${WORK}/full.pfm ${WORK}/kept.pfm)
reuse_counts(k ${WORK}/kept.json)
if(NOT k_changed EQUAL 0 OR NOT k_recomputed EQUAL 0 OR NOT kept_out MATCHES "reuse \\(the last frame\\): 0 of")
  message(FATAL_ERROR "an unchanged frame reports changed ${k_changed}, recomputed ${k_recomputed}\n${kept_out}")
endif()
# frames alternate the depth and the moved depth: the second and fourth are the moved one
cacao_ok(moved_alone --scene ${ROOM} --quality high --move-box 40,30,60,40 --warmup 1 --repeat 1 -o ${WORK}/moved1.pfm)
cacao_ok(moved --scene ${ROOM} --quality high --reuse --keep-output --move-box 40,30,60,40 --validate --warmup 1
         --repeat 3 --json ${WORK}/moved.json -o ${WORK}/moved.pfm)
expect_same_file("--reuse --move-box, the moved frame" ${WORK}/moved1.pfm ${WORK}/moved.pfm)
reuse_counts(m ${WORK}/moved.json)
if(NOT m_changed GREATER 0 OR NOT m_changed LESS m_tiles)
  message(FATAL_ERROR "--move-box: ${m_changed} of ${m_tiles} tiles changed, expected some")
endif()
cacao_ok(camera --scene ${ROOM} --quality high --reuse --move-camera --warmup 1 --repeat 2 --json ${WORK}/camera.json
         -o ${WORK}/camera.pfm)
reuse_counts(c ${WORK}/camera.json)
if(NOT c_changed EQUAL c_tiles)
  message(FATAL_ERROR "--move-camera: ${c_changed} of ${c_tiles} tiles changed, expected all")
endif()
cacao_run(r --scene ${ROOM} --reuse --move-box 0,0,100000,5 -o ${WORK}/no.pfm)
if(r_rc EQUAL 0 OR NOT r_err MATCHES "--move-box 0,0,100000,5" OR EXISTS ${WORK}/no.pfm)
  message(FATAL_ERROR "a box outside the depth: rc ${r_rc}, stderr '${r_err}'")
endif()
cacao_run(r --scene ${ROOM} --keep-output -o ${WORK}/no.pfm)
if(r_rc EQUAL 0 OR NOT r_err MATCHES "--keep-output: only with --reuse" OR EXISTS ${WORK}/no.pfm)
  message(FATAL_ERROR "--keep-output without --reuse: rc ${r_rc}, stderr '${r_err}'")
endif()
