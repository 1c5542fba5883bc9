# raster_flags: cacao-raster refuses a bad command line the way the project's tools do: a non-zero
# exit, one line on stderr that names the flag (or argument) and its value, nothing on stdout, and
# no output file, since the flags are checked before any device work. The cases are the example's
# flags with a missing, malformed or out-of-range value, and unknown ones.
# Takes RASTER (the example) and WORK (a scratch folder).
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
file(WRITE ${WORK}/a-file "")
set(png ${WORK}/never.png)
# Each case: the arguments (separated by spaces), then '|' and what the line must contain. Every
# run starts with a valid -o, which the refusal must leave unwritten.
set(cases
  "--bogus|--bogus: unknown flag"
  "stray|stray: unexpected argument"
  "-o|-o: needs a value"
  "-o ${WORK}/x.jpg|x.jpg: must name a .png file"
  "--depth-format d16|--depth-format d16: use d32 or d24s8"
  "--depth-format|--depth-format: needs a value"
  "--dump-frame 3|--dump-frame: needs --dump DIR"
  "--dump ${WORK}/d --dump-frame 30|--dump-frame 30: must be 0 to 29"
  "--dump ${WORK}/d --dump-frame 2x|--dump-frame 2x: must be 0 to 29"
  "--dump ${WORK}/a-file|a-file: not a directory"
  "--dump ${WORK}/no/such/folder|cannot create it")
foreach(case ${cases})
  string(FIND "${case}" "|" bar)
  string(SUBSTRING "${case}" 0 ${bar} args)
  math(EXPR bar "${bar} + 1")
  string(SUBSTRING "${case}" ${bar} -1 needle)
  separate_arguments(args UNIX_COMMAND "${args}")
  execute_process(COMMAND ${RASTER} -o ${png} ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  TIMEOUT 60)
  string(REGEX REPLACE "\n$" "" line "${err}")
  string(FIND "${line}" "${needle}" at)
  if(rc EQUAL 0 OR at LESS 0 OR line MATCHES "\n" OR NOT out STREQUAL "")
    message(FATAL_ERROR "cacao-raster ${args}: expected a failure with one line naming '${needle}', got exit "
                        "${rc}, stderr '${err}', stdout '${out}'")
  endif()
  if(EXISTS ${png} OR EXISTS ${WORK}/d/depth.pfm)
    message(FATAL_ERROR "cacao-raster ${args}: wrote output although it refused the command line")
  endif()
endforeach()
list(LENGTH cases count)
message("cacao-raster refused all ${count} command lines with one line each")
