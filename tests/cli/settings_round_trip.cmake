# --print-settings writes the effective settings as literal values, so feeding them back through
# --settings must reproduce them exactly (same printed JSON) and render the same AO bit for bit;
# literal zeros (--horizon 0, --blur 0, fade-out from 0) must survive the trip as zeros rather than
# turning into defaults. Flags override the file wherever they stand (here before --settings), and
# the scene's ao_radius_world is the default radius.
include(${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake)
set(FLAGS --quality medium --horizon 0 --blur 0 --fade-out 0,40 --strength 1.25 --detail 0)
cacao_ok(a --scene ${ROOM} ${FLAGS} --print-settings)
file(WRITE ${WORK}/a.json "${a_out}")
cacao_ok(b --scene ${ROOM} --settings ${WORK}/a.json --print-settings)
if(NOT a_out STREQUAL b_out)
  message(FATAL_ERROR "settings changed on the round trip:\n${a_out}\n---\n${b_out}")
endif()
foreach(pair "quality;medium" "horizon_angle_threshold;0" "blur_pass_count;0" "fade_out_from;0" "fade_out_to;40"
        "shadow_multiplier;1.25" "detail_shadow_strength;0" "radius;0.5" "generate_normals;OFF")
  list(GET pair 0 key)
  list(GET pair 1 expected)
  string(JSON value GET "${a_out}" ${key})
  if(NOT value STREQUAL expected)
    message(FATAL_ERROR "printed ${key} = ${value}, expected ${expected}")
  endif()
endforeach()

cacao_ok(pa --scene ${ROOM} ${FLAGS} --validate -o ${WORK}/a.pfm)
cacao_ok(pb --scene ${ROOM} --settings ${WORK}/a.json --validate -o ${WORK}/b.pfm)
mean_abs_diff(d ${WORK}/a.pfm ${WORK}/b.pfm)
expect_between("AO from flags vs from the printed settings, mean |diff|" ${d} 0 0)

cacao_ok(c --scene ${ROOM} --quality low --settings ${WORK}/a.json --print-settings)
string(JSON quality GET "${c_out}" quality)
string(JSON horizon GET "${c_out}" horizon_angle_threshold)
if(NOT quality STREQUAL "low" OR NOT horizon STREQUAL "0")
  message(FATAL_ERROR "a flag before --settings should override the file (quality ${quality}, horizon ${horizon})")
endif()
