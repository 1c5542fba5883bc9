# cacao-bench writes its files all or nothing, and checks that it can before the first frame
# (issue 35, defects 4 and 5). Every output is created empty beside its destination before the run
# and renamed into place only when all are complete, so:
#   - an output that cannot be created (a missing folder, a folder in the way, no gnuplot for
#     --plot) is refused before the first frame: these runs ask for 100000 frames and must still
#     end within the 60 s the helper allows;
#   - a failure after the run (gnuplot failing on the plot, simulated by a stand-in on PATH) is one
#     line, not gnuplot's transcript, and leaves the old --json, --csv and --save-ao files as they
#     were and nothing new: no plot, no AO image, no staged file;
#   - a run that succeeds replaces every old file. Inputs: BENCH, TOOL, WORK.
include(${CMAKE_CURRENT_LIST_DIR}/bench_common.cmake)
set(scene ${WORK}/s)
tiny_scene(${scene})
file(MAKE_DIRECTORY ${WORK}/ao ${WORK}/folder.png ${WORK}/no-gnuplot)
file(WRITE ${WORK}/old.json "the old JSON")
file(WRITE ${WORK}/old.csv "the old CSV")
file(WRITE ${WORK}/ao/s.lowest_native.pfm "the old AO")
file(WRITE ${WORK}/fake/gnuplot "#!/bin/sh
# a gnuplot that passes the check before the run (-e) and fails on the plot after it
[ \"$1\" = \"-e\" ] && exit 0
printf 'plot ...\\n      ^\\n\"%s\" line 12: simulated failure\\n\\nand more of its transcript\\n' \"$1\" >&2
exit 1
")
file(COPY ${WORK}/fake/gnuplot DESTINATION ${WORK}/bin FILE_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE)
snapshot(before ${WORK})

# ---- Refused before the first frame ----
set(long --scene ${scene} --configs lowest_native --repeat 100000 --warmup 100000)
set(old --json ${WORK}/old.json --csv ${WORK}/old.csv --save-ao ${WORK}/ao)
expect_bench_refused("--plot ${WORK}/nodir/p.png: cannot create a file there: No such file or directory" ${long} ${old}
                     --plot ${WORK}/nodir/p.png)
expect_bench_refused("--json ${WORK}/nodir/r.json: cannot create a file there" ${long} --json ${WORK}/nodir/r.json)
expect_bench_refused("--plot ${WORK}/folder.png: is a folder" ${long} ${old} --plot ${WORK}/folder.png)
expect_program_refused("${CMAKE_COMMAND};-E;env;PATH=${WORK}/no-gnuplot;${BENCH}" "cannot run gnuplot" ${long}
                       ${old} --plot ${WORK}/p.png)
expect_unchanged("outputs refused before the run" ${WORK} "${before}")

# ---- A failure after the run: the old files stay, nothing new ----
set(two --scene ${scene} --configs lowest_native,low_native --repeat 1 --warmup 0)
expect_program_refused("${CMAKE_COMMAND};-E;env;PATH=${WORK}/bin:$ENV{PATH};${BENCH}"
                       "--plot ${WORK}/new.png: gnuplot failed: simulated failure" ${two} ${old} --plot ${WORK}/new.png)
expect_unchanged("a plot failing after the run" ${WORK} "${before}")

# ---- Success replaces every old file ----
bench_ok(${two} ${old} --plot ${WORK}/new.png)
file(READ ${WORK}/old.json json)
string(JSON results LENGTH "${json}" results)
file(READ ${WORK}/old.csv csv)
file(READ ${WORK}/ao/s.lowest_native.pfm ao LIMIT 2)
if(NOT results EQUAL 2 OR NOT csv MATCHES "^scene,config," OR NOT ao MATCHES "^Pf" OR NOT EXISTS ${WORK}/new.png OR
   NOT EXISTS ${WORK}/ao/s.low_native.pfm)
  message(FATAL_ERROR "a successful run did not replace the old files (${results} results, AO '${ao}')")
endif()
expect_no_files("staged files left behind" ${WORK}/*.tmp)
