# No output of cacao-bench may name one of its inputs or another output (issue 35, defect 3): the
# report would replace a scene's depth or truth, or two reports would keep only one of them. The
# same file is recognised however it is spelled: the same text, "./" or "dir/../dir" spellings of
# a file not there yet (same folder, same name), and a hard link (same st_dev and st_ino). Each case
# is refused before the run with one line naming both flags, and nothing in the folder changes.
# The cacao command checks a --scene folder's files the same way (its -o once replaced depth.pfm).
# Two --scene folders with the same name (issue 35, defect 9) would write the same --save-ao files
# and be told apart nowhere in the JSON, so the second is refused. Inputs: BENCH, CACAO, TOOL, WORK.
include(${CMAKE_CURRENT_LIST_DIR}/bench_common.cmake)
set(scene ${WORK}/s)
tiny_scene(${scene})
file(MAKE_DIRECTORY ${WORK}/ao)
file(WRITE ${WORK}/ref.json "{\"name\": \"r\", \"points\": []}")
file(WRITE ${WORK}/from.png "{\"scenes\": [{\"name\": \"s\", \"truths\": [\"ao_gt\"]}], \"configurations\": [{\"name\": \"c\"}],
 \"results\": [{\"scene\": \"s\", \"config\": \"c\", \"total_ms\": 1, \"errors\": {\"ao_gt\": {\"rmse\": 0.1}}}]}")
file(WRITE ${WORK}/linked "a file with two names")
file(CREATE_LINK ${WORK}/linked ${WORK}/link2)
snapshot(before ${WORK})

set(in --scene ${scene} ${RUN1})
expect_bench_refused("--json ${scene}/depth.pfm: is also the --scene input" ${in} --json ${scene}/depth.pfm)
expect_bench_refused("--csv s/./ao_gt.pfm: is also the --scene input ${scene}/ao_gt.pfm" ${in} --csv s/./ao_gt.pfm)
expect_bench_refused("is also the --scene input ${scene}/camera.json" ${in} --json s/../s/camera.json)
expect_bench_refused("--json ${WORK}/ref.json: is also the --reference input" ${in} --reference ${WORK}/ref.json
                     --json ${WORK}/ref.json)
expect_bench_refused("--json r.json and --csv r.json name the same file" ${in} --json r.json --csv r.json)
expect_bench_refused("--json ./r.json and --csv r.json name the same file" ${in} --json ./r.json --csv r.json)
expect_bench_refused("--json ao/../p.svg and --plot p.svg name the same file" ${in} --json ao/../p.svg --plot p.svg)
expect_bench_refused("--json linked and --csv link2 name the same file" ${in} --json linked --csv link2)
expect_bench_refused("--json ao/s.lowest_native.pfm and --save-ao ao/s.lowest_native.pfm name the same file" ${in}
                     --save-ao ao --json ao/s.lowest_native.pfm)
expect_bench_refused("--plot ./from.png: is also the --plot-from input from.png" --plot-from from.png --plot ./from.png)
expect_unchanged("refused output paths" ${WORK} "${before}")

# cacao -o into its --scene folder.
expect_cacao_refused("--output s/depth.pfm: is also the --scene input" --scene s -o s/depth.pfm)
expect_cacao_refused("--json ./s/camera.json: is also the --scene input" --scene s --json ./s/camera.json)
expect_unchanged("cacao's refused output paths" ${WORK} "${before}")

# Two scenes named alike.
file(COPY ${scene}/ DESTINATION ${WORK}/other/s)
snapshot(before ${WORK})
expect_bench_refused("--scene ${WORK}/other/s/: named 's' like --scene ${scene}" --scene ${scene} --scene
                     ${WORK}/other/s/ ${RUN1} --save-ao ao --json r.json)
expect_unchanged("two scenes named alike" ${WORK} "${before}")
