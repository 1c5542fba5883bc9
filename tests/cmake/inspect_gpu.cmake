# `cacao-inspect gpu` refuses what it cannot do with one line naming the problem and exit 1: no
# --config or --all, an unknown flag or configuration, a bad size or normals source, a missing or
# malformed --amd file, a device index that does not exist, a named device without
# VK_KHR_pipeline_executable_properties (lavapipe) and no such device at all (only lavapipe's ICD
# loaded). Where RADV's ICD file exists it also runs on RADV's null device (navi21) with an --amd
# file written here, in which every AMD pipeline claims an inverse throughput of 64 cycles per
# wave64: AMD's estimate of a step is then one cycle per invocation, so its totals are counts
# worked out by hand from AMD's dispatches (FFX_CACAO_VkDraw at 1920x1080), independent of the tool.
# Inputs: INSPECT, RADV_ICD, WORK, RUN_ENV (optional: see inspect_common.cmake).
include(${CMAKE_CURRENT_LIST_DIR}/inspect_common.cmake)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

# refused(message args...): cacao-inspect gpu ARGS exits 1 with one stderr line containing message.
function(refused message)
  inspect(1 gpu ${ARGN})
  string(STRIP "${err}" line)
  if(NOT line MATCHES "^cacao-inspect: gpu: " OR line MATCHES "\n")
    message(FATAL_ERROR "gpu ${ARGN}: expected one line 'cacao-inspect: gpu: ...', got:\n${err}")
  endif()
  string(FIND "${line}" "${message}" at)
  if(at LESS 0)
    message(FATAL_ERROR "gpu ${ARGN}: expected '${message}' in: ${line}")
  endif()
endfunction()

refused("needs --config NAME or --all")
refused("unknown argument '--frobnicate'" --all --frobnicate)
refused("'nope' matches no configuration" --config nope)
refused("--size 0x5: not WxH" --all --size 0x5)
refused("--size 20000x10: not WxH" --all --size 20000x10)
refused("--json: needs a value" --all --json)
refused("--normals sideways: use depth or input" --all --normals sideways)
refused("--amd ${WORK}/absent.jsonl: cannot open" --all --amd ${WORK}/absent.jsonl)
file(WRITE ${WORK}/bad.jsonl "{\"entry\": \"FFX_CACAO_Apply\"}\n")
refused("--amd ${WORK}/bad.jsonl: line 1 is not" --all --amd ${WORK}/bad.jsonl)
refused("--device 99: no such Vulkan device" --all --device 99)
file(GLOB lavapipe_icd /usr/share/vulkan/icd.d/lvp_icd.*.json)
if(lavapipe_icd)
  set(ENV{VK_ICD_FILENAMES} "${lavapipe_icd}")
  refused("does not offer VK_KHR_pipeline_executable_properties" --all --device llvmpipe)
  refused("no Vulkan device offers VK_KHR_pipeline_executable_properties" --all)
  unset(ENV{VK_ICD_FILENAMES})
endif()
inspect(0 gpu --help)

if(NOT EXISTS "${RADV_ICD}")
  message("cacao-inspect gpu: errors checked; RADV's ICD file ${RADV_ICD} is absent: no null-device run")
  return()
endif()
set(ENV{VK_ICD_FILENAMES} "${RADV_ICD}")
set(ENV{RADV_FORCE_FAMILY} navi21)
set(ENV{MESA_SHADER_CACHE_DISABLE} true)
set(amd "")
foreach(entry ClearLoadCounter PrepareNativeDepthsHalf PrepareNativeNormals GenerateQ0 EdgeSensitiveBlur2
        NonSmartHalfApply PrepareNativeDepthsAndMips GenerateQ3Base GenerateImportanceMap
        PostprocessImportanceMapA PostprocessImportanceMapB GenerateQ3 Apply)
  string(APPEND amd "{\"entry\": \"FFX_CACAO_${entry}\", \"executable\": 0, \"stats\": {\"VGPRs\": 32, "
                    "\"Inverse Throughput\": 64}}\n")
endforeach()
file(WRITE ${WORK}/amd.jsonl "${amd}")
inspect(0 gpu --config lowest_native,highest_native --amd ${WORK}/amd.jsonl --json ${WORK}/gpu.json)
file(READ ${WORK}/gpu.json json)
# Invocations AMD dispatches at 1920x1080 (groups x numthreads, the grids rounded up):
# lowest_native: clear 1; depths (half) and normals 120x68 groups of 8x8 each, i.e. 960x544; Q0 on
# two slices, its sparse grid 48 x 34 x 5 groups of 4x16; blur 2 on two slices, 16 x 13 groups of
# 16x16; apply 240x135 groups of 8x8, i.e. 1920x1080.
# highest_native: clear 1; depths with mips and normals 960x544 each; the base pass and Q3 on four
# slices each, 8 x 960x544; three importance passes of 60x34 groups, i.e. 480x272; blur 2 on four
# slices; apply 1920x1080.
math(EXPR lowest "1 + 2 * 960 * 544 + 2 * 48 * 34 * 5 * 64 + 2 * 16 * 13 * 256 + 1920 * 1080")
math(EXPR highest "1 + 2 * 960 * 544 + 8 * 960 * 544 + 3 * 480 * 272 + 4 * 16 * 13 * 256 + 1920 * 1080")
foreach(i 0 1)
  string(JSON name GET "${json}" configurations ${i} name)
  string(JSON total GET "${json}" configurations ${i} amd total_cycles)
  string(JSON cacao GET "${json}" configurations ${i} cacao total_cycles)
  string(REGEX REPLACE "_native$" "" level "${name}")
  if(NOT total EQUAL ${level})
    message(FATAL_ERROR "${name}: AMD total ${total}, expected ${${level}} (one cycle per invocation)")
  endif()
  if(NOT cacao GREATER 0)
    message(FATAL_ERROR "${name}: cacao's estimate is ${cacao}")
  endif()
endforeach()
string(JSON measured LENGTH "${json}" permutations)
string(JSON stat GET "${json}" permutations 0 stats "Inverse Throughput")
if(measured LESS 5 OR NOT stat GREATER 0)
  message(FATAL_ERROR "the JSON lacks permutations or their statistics:\n${json}")
endif()
# The GPU form's prepare downsampled classifies in groups of its own (its dispatch's z 0): the
# estimate weighs them as classify_gpu.downsampled over the same groups, in the classify stage, and
# leaves the rest of the step's figure (both sides of the branch) to the prepare.
inspect(0 gpu --config low_downsampled --normals depth --json ${WORK}/gpu_ds.json)
file(READ ${WORK}/gpu_ds.json json)
string(JSON count LENGTH "${json}" permutations)
math(EXPR last "${count} - 1")
set(cls_it "")
foreach(i RANGE ${last})
  string(JSON key GET "${json}" permutations ${i} key)
  if(key STREQUAL "classify_gpu.downsampled")
    string(JSON cls_it GET "${json}" permutations ${i} stats "Inverse Throughput")
  endif()
endforeach()
string(JSON steps LENGTH "${json}" configurations 0 cacao steps)
math(EXPR last "${steps} - 1")
set(prep "")
set(split "")
foreach(i RANGE ${last})
  string(JSON name GET "${json}" configurations 0 cacao steps ${i} name)
  string(JSON cycles GET "${json}" configurations 0 cacao steps ${i} cycles)
  string(JSON stage GET "${json}" configurations 0 cacao steps ${i} stage)
  if(name STREQUAL "prepare_gpu.full.downsampled")
    string(JSON gx GET "${json}" configurations 0 cacao steps ${i} groups 0)
    string(JSON gy GET "${json}" configurations 0 cacao steps ${i} groups 1)
    string(JSON gz GET "${json}" configurations 0 cacao steps ${i} groups 2)
    string(JSON it GET "${json}" configurations 0 cacao steps ${i} inverse_throughput)
    set(prep ${cycles})
  elseif(name MATCHES "^classify_gpu.downsampled" AND stage STREQUAL "classify/compact")
    set(split ${cycles})
  endif()
endforeach()
if(cls_it STREQUAL "" OR prep STREQUAL "" OR split STREQUAL "" OR NOT gz EQUAL 2)
  message(FATAL_ERROR "low_downsampled: no prepare_gpu step over 2 z groups and classification share:\n${json}")
endif()
math(EXPR want_split "${gx} * ${gy} * ${cls_it}")
math(EXPR sum "${prep} + ${split}")
math(EXPR want_sum "${gx} * ${gy} * ${gz} * ${it}")
if(NOT split EQUAL want_split OR NOT sum EQUAL want_sum)
  message(FATAL_ERROR "low_downsampled: classification share ${split} (expected ${want_split}), prepare and share ${sum} (expected ${want_sum})")
endif()
message("cacao-inspect gpu: errors checked; on RADV navi21 AMD's estimate is one cycle per invocation; "
        "the downsampled prepare's classification groups weighed as classify_gpu")
