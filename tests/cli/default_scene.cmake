# With no input flags, cacao renders its embedded default scene at 1280x720 and writes an 8-bit
# cacao-out.png into the current directory, naming it on stdout: the zero-argument run is the
# documented first contact with the tool. The PNG is read back with the project's own PNG reader
# (cli_tool info) to check its size, channels and depth. Run with --validate (which renders the
# same thing) so that the layer checks the full-size frame.
include(${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake)
cacao_ok(run --validate)
if(NOT run_out MATCHES "cacao-out\\.png")
  message(FATAL_ERROR "stdout does not name the file it wrote: ${run_out}")
endif()
if(NOT EXISTS ${WORK}/cacao-out.png)
  message(FATAL_ERROR "cacao-out.png was not written in the working directory")
endif()
tool(info info ${WORK}/cacao-out.png)
if(NOT info STREQUAL "1280 720 1 8")
  message(FATAL_ERROR "cacao-out.png is '${info}', expected 1280x720, 1 channel, 8 bits")
endif()
file(GLOB leftovers ${WORK}/*.tmp)
if(leftovers)
  message(FATAL_ERROR "temporary files left behind: ${leftovers}")
endif()
