# shadergen reports a compile error with the permutation key and the source file and line, exits
# non-zero and writes nothing. The broken source is cacao.comp plus one bad line that only the blur
# permutations compile, so the line number and the keys are known in advance. A second copy whose
# #include names a missing file fails the same way, naming the including file, line and name.
# Inputs: SHADERGEN, SOURCE (shaders/cacao.comp; its folder is copied, with what it includes), WORK.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/out)
get_filename_component(source_dir ${SOURCE} DIRECTORY)
file(COPY ${source_dir}/cacao_shared.h ${source_dir}/glsl DESTINATION ${WORK})
file(READ ${SOURCE} text)
string(REGEX MATCHALL "\n" newlines "${text}")
list(LENGTH newlines lines)
math(EXPR bad_line "${lines} + 2")
file(WRITE ${WORK}/cacao.comp "${text}#if CACAO_PASS == CACAO_PASS_BLUR\nthis_is_not_glsl x = ;\n#endif\n")
execute_process(COMMAND ${SHADERGEN} --source ${WORK}/cacao.comp --out ${WORK}/out
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0)
  message(FATAL_ERROR "shadergen accepted a broken source")
endif()
foreach(needle "blur.1.fp32: GLSL compilation failed" "blur.8.fp16: GLSL compilation failed"
        "cacao.comp:${bad_line}" "16 permutation(s) failed; nothing written")
  string(FIND "${err}" "${needle}" at)
  if(at LESS 0)
    message(FATAL_ERROR "expected '${needle}' in shadergen's errors:\n${err}")
  endif()
endforeach()
string(FIND "${err}" "generate.q2:" at)
if(NOT at LESS 0)
  message(FATAL_ERROR "a permutation without the bad line was reported:\n${err}")
endif()
file(GLOB written ${WORK}/out/*)
if(written)
  message(FATAL_ERROR "shadergen wrote files despite failing: ${written}")
endif()
message("shadergen names the key and cacao.comp:${bad_line}, exits ${rc}, writes nothing")

# An #include of a file that is not there: one message naming the includer, its line and the file.
file(WRITE ${WORK}/missing.comp "#version 450\n#include \"glsl/no_such_file.glsl\"\n")
execute_process(COMMAND ${SHADERGEN} --source ${WORK}/missing.comp --out ${WORK}/out
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0)
  message(FATAL_ERROR "shadergen accepted a source that includes a missing file")
endif()
string(FIND "${err}" "glsl/no_such_file.glsl" at)
if(at LESS 0)
  message(FATAL_ERROR "expected the missing file's name in shadergen's error:\n${err}")
endif()
file(GLOB written ${WORK}/out/*)
if(written)
  message(FATAL_ERROR "shadergen wrote files despite a missing include: ${written}")
endif()
message("a missing include: ${err}")
