# What a hostile tester broke in the command (issue 16), each case from its description:
#   - `-o` equal to `--json` or to an input is refused, and the input is left as it was;
#   - a failed --json (an unwritable folder) touches no existing file: the -o file the user had
#     keeps its bytes, and no staged file is left beside it;
#   - one NaN pixel in a --compare truth is skipped and counted: comparing a run with its own output
#     (one foreground pixel poked to NaN) gives rmse 0 over one pixel fewer, not "rmse nan";
#   - `--quality -o x.png` blames --quality (the flag missing its value), not x.png;
#   - control bytes in arguments, their values and JSON keys and values come out escaped, on one line;
#   - a directory or a FIFO given as an input is named as such at once (never a hang: the process
#     runs under a timeout), and "cannot open" carries the system's reason;
#   - settings JSON: a key given twice and trailing text are refused naming the key or position;
#     a bad value in the file that a flag overrides is not an error (flags override the file), while
#     the same file alone is refused.
include(${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake)
set(CAM --camera ${ROOM}/camera.json)

function(expect_same_bytes what path expected_text)
  file(READ ${path} now)
  if(NOT now STREQUAL expected_text)
    message(FATAL_ERROR "${what}: ${path} was changed")
  endif()
endfunction()

# ---- Output collisions (no device needed) ----
expect_cacao_refused("name the same file" --scene ${ROOM} -o ${WORK}/same.png --json ${WORK}/same.png)
file(COPY ${ROOM}/depth.pfm DESTINATION ${WORK})
file(READ ${WORK}/depth.pfm depth_before HEX)
expect_cacao_refused("is also the --depth input" --depth ${WORK}/depth.pfm ${CAM} -o ${WORK}/depth.pfm)
expect_cacao_refused("is also the --depth input" --depth depth.pfm ${CAM} -o ${WORK}/depth.pfm)
file(COPY ${ROOM}/camera.json DESTINATION ${WORK})
expect_cacao_refused("is also the --camera input" --depth ${WORK}/depth.pfm --camera ${WORK}/camera.json -o x.png
               --json ${WORK}/camera.json)
file(READ ${WORK}/depth.pfm depth_after HEX)
if(NOT depth_before STREQUAL depth_after)
  message(FATAL_ERROR "the --depth input was changed by a refused run")
endif()

# ---- A failed --json leaves an existing -o file alone ----
file(WRITE ${WORK}/keep.png "the user's own file")
expect_cacao_refused("r.json" --scene ${ROOM} --validate -o ${WORK}/keep.png --json ${WORK}/no/such/folder/r.json)
expect_same_bytes("failed --json" ${WORK}/keep.png "the user's own file")
file(GLOB staged ${WORK}/keep.png.* ${WORK}/*.new ${WORK}/*.tmp)
if(staged)
  message(FATAL_ERROR "failed --json left staged files: ${staged}")
endif()

# ---- NaN in the truth: skipped and counted ----
cacao_ok(first --scene ${ROOM} --validate -o ${WORK}/ao.pfm)
tool(ignored poke ${WORK}/ao.pfm ${WORK}/truth.pfm 80 60 nan)
cacao_ok(second --scene ${ROOM} --validate -o ${WORK}/ao2.pfm --compare ${WORK}/truth.pfm --json ${WORK}/c.json)
message("${second_out}")
if(NOT second_out MATCHES "rmse 0.000000 " OR NOT second_out MATCHES "\\(1 non-finite truth pixels skipped\\)")
  message(FATAL_ERROR "--compare with one NaN truth pixel: expected rmse 0 and one skipped pixel: ${second_out}")
endif()
file(READ ${WORK}/c.json report)
string(JSON skipped GET "${report}" compare skipped_nonfinite_truth)
if(NOT skipped EQUAL 1)
  message(FATAL_ERROR "--json: compare.skipped_nonfinite_truth is ${skipped}, expected 1")
endif()

# ---- Messages ----
expect_cacao_refused("--quality: needs a value" --scene ${ROOM} --quality -o x.png)
string(ASCII 27 esc)
expect_cacao_refused("--\\x1b[2Jbad\\x0a: unknown flag" "--${esc}[2Jbad\n")
# Values too (issue 35, found by fuzz_cli_args): an unknown --quality, in a flag or a settings file.
expect_cacao_refused("--quality \\x1b[2J: unknown value '\\x1b[2J'" --scene ${ROOM} --quality "${esc}[2J")
file(WRITE ${WORK}/evil_value.json "{\"quality\": \"\\u001b[31m\"}")
expect_cacao_refused("\"quality\": unknown value '\\x1b[31m'" --scene ${ROOM} --settings ${WORK}/evil_value.json
                     --print-settings)
file(MAKE_DIRECTORY ${WORK}/dir.pfm)
expect_cacao_refused("dir.pfm: is a directory" --depth ${WORK}/dir.pfm ${CAM})
expect_cacao_refused("gone.pfm: cannot open: No such file or directory" --depth ${WORK}/gone.pfm ${CAM})
execute_process(COMMAND mkfifo ${WORK}/pipe.exr ${WORK}/pipe.json RESULT_VARIABLE fifo_rc)
if(NOT fifo_rc EQUAL 0)
  message(FATAL_ERROR "mkfifo failed")
endif()
expect_cacao_refused("pipe.exr: is not a regular file" --depth ${WORK}/pipe.exr ${CAM})
expect_cacao_refused("pipe.json: is not a regular file" --scene ${ROOM} --settings ${WORK}/pipe.json --print-settings)

# ---- Settings JSON ----
file(WRITE ${WORK}/twice.json "{\"radius\": 1.0, \"radius\": 2.0}")
expect_cacao_refused("twice.json: key \"radius\" is given more than once" --scene ${ROOM} --settings ${WORK}/twice.json
               --print-settings)
file(WRITE ${WORK}/trailing.json "{\"radius\": 1.0}\n}")
expect_cacao_refused("trailing.json: unexpected text after the JSON value at line 2, column 1" --scene ${ROOM} --settings
               ${WORK}/trailing.json --print-settings)
file(WRITE ${WORK}/evil_key.json "{\"ra${esc}[31mdius\": 1.0}")
expect_cacao_refused("\"ra\\x1b[31mdius\": unknown setting" --scene ${ROOM} --settings ${WORK}/evil_key.json --print-settings)
file(WRITE ${WORK}/bad_radius.json "{\"radius\": -3, \"blur_pass_count\": 3}")
expect_cacao_refused("bad_radius.json: \"radius\"" --scene ${ROOM} --settings ${WORK}/bad_radius.json --print-settings)
cacao_ok(merged --scene ${ROOM} --settings ${WORK}/bad_radius.json --radius 0.7 --print-settings)
string(JSON radius GET "${merged_out}" radius)
string(JSON blur GET "${merged_out}" blur_pass_count)
if(NOT radius EQUAL 0.7 OR NOT blur EQUAL 3)
  message(FATAL_ERROR "settings file + overriding flag: expected radius 0.7 and blur_pass_count 3: ${merged_out}")
endif()
