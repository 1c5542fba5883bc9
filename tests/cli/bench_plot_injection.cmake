# Text from the inputs never becomes gnuplot commands (issue 35, defect 2). Names are data: the plot
# script spells them as string literals with every unusual byte octal-escaped and the data file
# holds numbers only. So a reference name or point label, and a --plot-from scene or configuration
# name, holding a backquoted shell command (which gnuplot runs even inside double quotes), quotes,
# a backslash, @ and $ are drawn as text: the run exits 0 and the file the command would create
# never appears. A name with a line break or an escape byte, which no title or table can show, is
# refused with one line naming the field, and leaves no plot. A scene folder with a space in its
# name plots (its name was once split into two panel titles). Inputs: BENCH, TOOL, WORK.
include(${CMAKE_CURRENT_LIST_DIR}/bench_common.cmake)
set(scene ${WORK}/room)
tiny_scene(${scene})
set(proof ran) # what an injected command would create, in WORK (where the bench and gnuplot run)

# Fails unless path is an image of the kind its extension says and no injected command ran.
function(expect_plot_and_no_command path)
  file(READ ${path} head LIMIT 8 HEX)
  if(path MATCHES "\\.png$" AND NOT head STREQUAL "89504e470d0a1a0a")
    message(FATAL_ERROR "${path} is not a PNG (starts ${head})")
  endif()
  if(path MATCHES "\\.svg$")
    file(READ ${path} text)
    if(NOT text MATCHES "<svg")
      message(FATAL_ERROR "${path} is not an SVG")
    endif()
  endif()
  expect_no_files("a name from the inputs ran as a command" ${WORK}/${proof}*)
endfunction()

# ---- --reference: name and label with commands, quotes, backslash, @ and $ ----
file(WRITE ${WORK}/ref.json "{\"name\": \"AMD `touch ${proof}-name` \\\" \\\\ @x $y\", \"points\": [{\"scene\": \"room\", \"config\": \"amd `touch ${proof}-label`\", \"total_ms\": 1.0, \"rmse_ao_gt\": 0.1}]}")
bench_ok(--scene ${scene} ${RUN1} --reference ${WORK}/ref.json --plot ${WORK}/ref.png)
expect_plot_and_no_command(${WORK}/ref.png)

file(WRITE ${WORK}/ref_newline.json "{\"name\": \"AMD\\n!touch ${proof}-newline\", \"points\": []}")
expect_bench_refused("ref_newline.json: name: empty or holds control characters" --scene ${scene} ${RUN1}
                     --reference ${WORK}/ref_newline.json --plot ${WORK}/newline.png)
file(WRITE ${WORK}/ref_label.json "{\"name\": \"AMD\", \"points\": [{\"scene\": \"room\", \"config\": \"a\\u001b[2Jb\", \"total_ms\": 1}]}")
expect_bench_refused("ref_label.json: points[0].config: empty or holds control characters" --scene ${scene}
                     ${RUN1} --reference ${WORK}/ref_label.json --plot ${WORK}/label.png)

# ---- --plot-from: scene and configuration names with commands (no device needed) ----
set(result "\"total_ms\": 1.5, \"errors\": {\"ao_gt\": {\"rmse\": 0.1}}")
file(WRITE ${WORK}/from.json "{\"scenes\": [{\"name\": \"s `touch ${proof}-scene` 'q' @m\", \"truths\": [\"ao_gt\"]}],
 \"configurations\": [{\"name\": \"c `touch ${proof}-config`\"}, {\"name\": \"c2\"}],
 \"results\": [{\"scene\": \"s `touch ${proof}-scene` 'q' @m\", \"config\": \"c `touch ${proof}-config`\", ${result}},
               {\"scene\": \"s `touch ${proof}-scene` 'q' @m\", \"config\": \"c2\", \"total_ms\": 2.5}]}")
bench_ok(--plot-from ${WORK}/from.json --reference ${WORK}/ref.json --plot ${WORK}/from.svg)
expect_plot_and_no_command(${WORK}/from.svg)

file(WRITE ${WORK}/from_newline.json "{\"scenes\": [{\"name\": \"s\\nsystem('touch ${proof}-from')\", \"truths\": [\"ao_gt\"]}],
 \"configurations\": [{\"name\": \"c\"}], \"results\": [{\"scene\": \"s\\nsystem('touch ${proof}-from')\", \"config\": \"c\", ${result}}]}")
expect_bench_refused("from_newline.json: scenes[0].name: empty or holds control characters"
                     --plot-from ${WORK}/from_newline.json --plot ${WORK}/from_newline.png)
if(EXISTS ${WORK}/from_newline.png OR EXISTS ${WORK}/newline.png OR EXISTS ${WORK}/label.png)
  message(FATAL_ERROR "a refused name left a plot behind")
endif()

# ---- A scene folder with a space in its name ----
file(MAKE_DIRECTORY "${WORK}/my room")
file(COPY ${scene}/ DESTINATION "${WORK}/my room")
bench_ok(--scene "${WORK}/my room" ${RUN1} --plot ${WORK}/space.png)
expect_plot_and_no_command(${WORK}/space.png)
