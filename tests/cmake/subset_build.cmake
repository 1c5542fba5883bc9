# A subset build (-DCACAO_QUALITIES=medium;high -DCACAO_DOWNSAMPLE=OFF -DCACAO_PRECISION=fp32)
# generates its own table in its build tree holding exactly the permutations those settings can
# dispatch, and a lookup of a permutation outside it is a clear error.
# Inputs: SOURCE_DIR, WORK, GENERATOR.
file(REMOVE_RECURSE ${WORK})
set(qualities "medium;high")
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK} -G ${GENERATOR} -DCACAO_BUILD_TESTS=ON
                "-DCACAO_QUALITIES=${qualities}" -DCACAO_DOWNSAMPLE=OFF -DCACAO_PRECISION=fp32
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the subset build failed:\n${out}${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK} --target table_dump test_missing_permutation cacao_inspect RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the subset failed:\n${out}${err}")
endif()
if(NOT EXISTS ${WORK}/generated/cacao_table.c)
  message(FATAL_ERROR "the subset build did not generate its own table in its build tree")
endif()
execute_process(COMMAND ${WORK}/tests/table_dump RESULT_VARIABLE rc OUTPUT_VARIABLE listing)
string(REGEX MATCHALL "[a-z_0-9.]+ [0-9]+ [0-9]+\n" lines "${listing}")
set(names "")
foreach(l ${lines})
  string(REGEX REPLACE " .*" "" name "${l}")
  list(APPEND names ${name})
endforeach()
# Expected by hand from the spec's quality table: MEDIUM = depths without mips, Q1, Apply;
# HIGH = depths with mips, Q2, Apply; either normals source (given: prepare_depths and
# prepare_normals, and at MEDIUM with reuse (CPU forms) Q1's variant that reads the caller's
# normals; from depth: prepare, both in one pass); blur 1..8; fp32 only; native only;
# every key of the horizon-slice estimators (full resolution, fp32, no quality axis) and the
# tile passes (no axis: every CACAO configuration runs them); and the GPU forms of the blur,
# apply, prepare and generate, and of the horizon estimators' passes (a build
# embeds both forms: the device chooses); the reuse passes (no axis: a setting of any CACAO
# configuration); the temporal passes (no axis: a setting of the horizon estimators).
set(expected prepare_depths.full.native prepare_depths.mips.native prepare_depths.mips_chain.native prepare_normals.native prepare_normals.list.native
    generate.q1 generate.q2 generate.q1_input blur.1.fp32 blur.2.fp32 blur.3.fp32
    blur.4.fp32 blur.5.fp32 blur.6.fp32 blur.7.fp32 blur.8.fp32 apply.smart.fp32 apply.smart_list.fp32
    horizon_prepare.depth horizon_prepare.input horizon_prepare.z horizon_main.gtao horizon_main.bitmask horizon_main.gtao_direct
    horizon_main.bitmask_direct horizon_denoise.intermediate horizon_denoise.final classify classify.horizon classify.quiet compact
    compact.horizon fill
    prepare.full.native prepare.mips.native
    blur_gpu.1.fp32 blur_gpu.2.fp32 blur_gpu.3.fp32 blur_gpu.4.fp32 blur_gpu.5.fp32 blur_gpu.6.fp32 blur_gpu.7.fp32
    blur_gpu.8.fp32 apply_gpu.smart.fp32 prepare_gpu.full.native prepare_gpu.mips.native generate_gpu.q1 generate_gpu.q2
    reuse.diff reuse.diff_normals reuse.prefix reuse.reach reuse.diff_gpu reuse.diff_normals_gpu
    horizon_prepare_gpu.depth horizon_prepare_gpu.input horizon_main_gpu.gtao horizon_main_gpu.bitmask
    horizon_main_gpu.gtao_direct horizon_main_gpu.bitmask_direct horizon_denoise_gpu.intermediate
    horizon_denoise_gpu.final classify_gpu.native horizon_temporal)
if(NOT names STREQUAL expected)
  message(FATAL_ERROR "subset table holds [${names}]\nexpected [${expected}]")
endif()
list(LENGTH expected expected_count)
execute_process(COMMAND ${WORK}/tests/table_dump --find generate.q3 RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "generate.q3' is not embedded in this build")
  message(FATAL_ERROR "looking up a permutation outside the subset should fail clearly, got rc=${rc}: ${err}")
endif()
execute_process(COMMAND ${WORK}/tests/test_missing_permutation ${expected_count} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the runtime did not refuse permutations outside the subset clearly")
endif()
execute_process(COMMAND ${WORK}/tools/inspect/cacao-inspect stats OUTPUT_VARIABLE stats RESULT_VARIABLE rc)
string(FIND "${stats}" "permutations: ${expected_count} before dedup" at)
if(NOT rc EQUAL 0 OR at LESS 0)
  message(FATAL_ERROR "cacao-inspect stats in the subset build does not report the ${expected_count} expected permutations:\n${stats}")
endif()
execute_process(COMMAND ${WORK}/tools/inspect/cacao-inspect verify OUTPUT_VARIABLE verify RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cacao-inspect verify fails in the subset build:\n${verify}")
endif()
message("${stats}${verify}")
message("subset table holds exactly the ${expected_count} expected permutations; missing lookup says: ${err}")
