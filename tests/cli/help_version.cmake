# --help documents every flag the settings table defines (each settings flag named in the issue
# must appear) and --version prints the version and the embedded permutation count; both exit 0
# without touching a device.
include(${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake)
cacao_ok(help --help)
foreach(flag --scene --depth --normals --camera --fov --near --far --reverse-z --output --png16 --bits --compare
        --timings --repeat --json --print-settings --settings --quality --downsample --blur --radius --strength
        --power --clamp --horizon --fade-out --sharpness --detail --adaptive-limit --bilateral-sigma
        --bilateral-similarity --precision --no-normals --device --list-devices --validate --version)
  if(NOT help_out MATCHES "${flag}[ ,\n]")
    message(FATAL_ERROR "--help does not document ${flag}")
  endif()
endforeach()
cacao_ok(version --version)
if(NOT version_out MATCHES "^cacao [0-9]+\\.[0-9]+\\.[0-9]+ \\(([0-9]+) embedded shader permutations\\)")
  message(FATAL_ERROR "unexpected --version output: ${version_out}")
endif()
if(CMAKE_MATCH_1 LESS 1)
  message(FATAL_ERROR "--version reports no embedded permutations")
endif()
