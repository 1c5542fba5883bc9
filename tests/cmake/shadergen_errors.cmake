# shadergen reports a compile error with the permutation key and the source file and line, exits
# non-zero and writes nothing. The broken source is cacao.comp plus one bad line that only the blur
# permutations compile, so the line number and the keys are known in advance.
# Inputs: SHADERGEN, SOURCE, SHARED, WORK.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/out)
file(READ ${SOURCE} text)
string(REGEX MATCHALL "\n" newlines "${text}")
list(LENGTH newlines lines)
math(EXPR bad_line "${lines} + 2")
file(WRITE ${WORK}/cacao.comp "${text}#if CACAO_PASS == CACAO_PASS_BLUR\nthis_is_not_glsl x = ;\n#endif\n")
execute_process(COMMAND ${SHADERGEN} --source ${WORK}/cacao.comp --shared ${SHARED} --out ${WORK}/out
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
