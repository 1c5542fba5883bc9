# --reuse (docs/tiles.md "Reusing the previous frame") through the command: the last of several
# frames of the same depth is the frame computed alone, byte for byte, and reports no tile changed;
# --move-box makes every frame after the first change some tiles and still gives the moved frame's
# own output (its last frame, the fourth, is the moved one: compared with the moved depth computed
# alone through the same flag and --repeat 1 --warmup 1, whose second frame is the moved one);
# --move-camera makes every frame a full one; a box outside the depth is one clear error and no
# output.
include(${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake)
cacao_ok(full --scene ${ROOM} --quality high -o ${WORK}/full.pfm)
cacao_ok(kept --scene ${ROOM} --quality high --reuse --keep-output --validate --warmup 1 --repeat 3 --timings
         --json ${WORK}/kept.json -o ${WORK}/kept.pfm)
file(SHA256 ${WORK}/full.pfm a)
file(SHA256 ${WORK}/kept.pfm b)
if(NOT a STREQUAL b)
  message(FATAL_ERROR "--reuse --keep-output: the unchanged frame's output differs from the frame computed alone")
endif()
file(READ ${WORK}/kept.json report)
string(JSON changed GET "${report}" tiles changed)
string(JSON recomputed GET "${report}" tiles recomputed)
if(NOT changed EQUAL 0 OR NOT recomputed EQUAL 0 OR NOT kept_out MATCHES "reuse \\(the last frame\\): 0 of")
  message(FATAL_ERROR "an unchanged frame reports changed ${changed}, recomputed ${recomputed}\n${kept_out}")
endif()
# frames alternate the depth and the moved depth: the second and fourth are the moved one
cacao_ok(moved_alone --scene ${ROOM} --quality high --move-box 40,30,60,40 --warmup 1 --repeat 1 -o ${WORK}/moved1.pfm)
cacao_ok(moved --scene ${ROOM} --quality high --reuse --keep-output --move-box 40,30,60,40 --validate --warmup 1
         --repeat 3 --json ${WORK}/moved.json -o ${WORK}/moved.pfm)
file(SHA256 ${WORK}/moved1.pfm a)
file(SHA256 ${WORK}/moved.pfm b)
if(NOT a STREQUAL b)
  message(FATAL_ERROR "--reuse --move-box: the moved frame's output differs from the same frame computed alone")
endif()
file(READ ${WORK}/moved.json report)
string(JSON changed GET "${report}" tiles changed)
string(JSON tiles GET "${report}" tiles tiles)
if(NOT changed GREATER 0 OR NOT changed LESS tiles)
  message(FATAL_ERROR "--move-box: ${changed} of ${tiles} tiles changed, expected some")
endif()
cacao_ok(camera --scene ${ROOM} --quality high --reuse --move-camera --warmup 1 --repeat 2 --json ${WORK}/camera.json
         -o ${WORK}/camera.pfm)
file(READ ${WORK}/camera.json report)
string(JSON changed GET "${report}" tiles changed)
string(JSON tiles GET "${report}" tiles tiles)
if(NOT changed EQUAL tiles)
  message(FATAL_ERROR "--move-camera: ${changed} of ${tiles} tiles changed, expected all")
endif()
cacao_run(r --scene ${ROOM} --reuse --move-box 0,0,100000,5 -o ${WORK}/no.pfm)
if(r_rc EQUAL 0 OR NOT r_err MATCHES "--move-box 0,0,100000,5" OR EXISTS ${WORK}/no.pfm)
  message(FATAL_ERROR "a box outside the depth: rc ${r_rc}, stderr '${r_err}'")
endif()
