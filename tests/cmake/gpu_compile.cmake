# gpu_compile_<family>: no embedded permutation a GPU runs uses scratch memory or spills registers
# when RADV's compiler (ACO) builds it for that AMD family: every permutation of the GPU shader
# forms (cacao_shader_forms; what a context on that device dispatches). The CPU forms (lavapipe's
# shapes of the blur and apply) are not checked: a GPU never runs them, and their register blocks
# do spill there (docs/gpu.md lists them). Scratch is per-lane memory traffic a register
# allocation avoids, so a spill means a permutation is too large for the GPU it targets. The test's
# ENVIRONMENT names the family (RADV_FORCE_FAMILY) and RADV's ICD file (VK_ICD_FILENAMES): RADV's
# null device compiles without a GPU. It is skipped where that ICD file is absent, and fails naming
# every permutation that spills (cacao-inspect gpu --all --no-spills) or could not be measured.
# Inputs: INSPECT, RUN_ENV (optional).
string(REPLACE "|" ";" run_env "${RUN_ENV}") # the sanitizer build's preloads, for cacao-inspect alone
if(NOT EXISTS "$ENV{VK_ICD_FILENAMES}")
  message("CACAO_SKIP: RADV's ICD file '$ENV{VK_ICD_FILENAMES}' is absent (Debian: mesa-vulkan-drivers)")
  return()
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E env ${run_env} ${INSPECT} gpu --all --no-spills RESULT_VARIABLE rc
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCH "device: [^\n]*" device "${out}")
string(REGEX MATCH "([0-9]+) of ([0-9]+) embedded permutations measured" measured "${out}")
if(NOT rc EQUAL 0)
  string(REGEX MATCHALL " spills on " spills "${err}")
  list(LENGTH spills count)
  if(count EQUAL 0)
    message(FATAL_ERROR "RADV_FORCE_FAMILY=$ENV{RADV_FORCE_FAMILY}: cacao-inspect gpu failed (exit ${rc}):\n${err}")
  endif()
  message("${err}") # as the tool wrote it: one line per permutation
  message(FATAL_ERROR "RADV_FORCE_FAMILY=$ENV{RADV_FORCE_FAMILY}: ${count} permutation(s) spill (above)")
endif()
if(NOT CMAKE_MATCH_1 EQUAL CMAKE_MATCH_2) # a permutation left unmeasured is a permutation unchecked
  string(REGEX MATCHALL "not measured: [^\n]*" missing "${out}")
  string(REPLACE ";" "\n" missing "${missing}")
  message(FATAL_ERROR "RADV_FORCE_FAMILY=$ENV{RADV_FORCE_FAMILY}: ${measured}\n${missing}")
endif()
message("RADV_FORCE_FAMILY=$ENV{RADV_FORCE_FAMILY}: ${device}; ${measured}; none uses scratch or spills")
