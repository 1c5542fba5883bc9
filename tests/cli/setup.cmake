# Setup (fixture cli_scenes): generates the scene folders the other CLI tests read, in the layout of
# shared/scenes (depth.pfm, depth_reversed.pfm, normals.pfm, camera.json): the default scene at
# 160x90 (room) and a camera-facing plane at 160x90 (plane), from the project's own CPU ray caster.
include(${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake)
file(REMOVE_RECURSE ${SCENES})
foreach(kind scene plane)
  if(kind STREQUAL "scene")
    set(dir ${ROOM})
  else()
    set(dir ${PLANE})
  endif()
  file(MAKE_DIRECTORY ${dir})
  tool(ignored ${kind} ${dir} 160 90)
endforeach()
