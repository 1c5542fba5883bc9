# raster_ao_equality: cacao inside a rendering engine gives, from the depth and normals that engine
# rasterized, exactly the AO the `cacao` command gives from the same depth, normals, projection and
# settings. The two share nothing but the library: the example records cacao between two graphics
# passes in one command buffer, on a D32 or D24S8 attachment and A2B10G10R10 normals, after two
# resizes and a settings change; the command uploads float images into a fresh context. On one
# device and in fp32 the arithmetic is the same, so any difference is an error in how the example
# hands its images to cacao (layouts, formats, projection, normals convention) or in cacao's state
# across resize and set_settings.
# Takes CACAO (the command), TOOL (cli_tool) and DIR (the folder cacao-raster --dump wrote).
foreach(file depth.pfm normals.pfm camera.json settings.json ao.pfm)
  if(NOT EXISTS ${DIR}/${file})
    message(FATAL_ERROR "${DIR}/${file} is missing: cacao-raster --dump did not write it")
  endif()
endforeach()
file(REMOVE ${DIR}/ref.pfm)
execute_process(COMMAND ${CACAO} --scene ${DIR} --settings ${DIR}/settings.json -o ${DIR}/ref.pfm --validate
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT err STREQUAL "")
  message(FATAL_ERROR "cacao --scene ${DIR} exited ${rc}\nstdout: ${out}\nstderr: ${err}")
endif()
execute_process(COMMAND ${TOOL} diff ${DIR}/ao.pfm ${DIR}/ref.pfm RESULT_VARIABLE rc OUTPUT_VARIABLE diff
                ERROR_VARIABLE err OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cli_tool diff: ${err}")
endif()
message("cacao-raster's AO against the cacao command's: ${diff}")
# Byte for byte (the same PFM writer): every float equal, which the printed maximum cannot show
# below 1e-9.
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${DIR}/ao.pfm ${DIR}/ref.pfm RESULT_VARIABLE differ)
if(NOT differ EQUAL 0)
  message(FATAL_ERROR "the AO differs: ${diff}")
endif()
