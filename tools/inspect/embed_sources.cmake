# Writes OUT: a C source defining `const sg_source cacao_inspect_sources[]` (and its count) with
# the text of each of FILES (names relative to ROOT, the entry source first), so cacao-inspect can
# show the shader source of this source tree, includes resolved, at build time. That is the source
# the embedded table was built from when generated/ is current: a subset build generates its table
# from it in the same build, and the generated_reproduces test regenerates the checked-in
# generated/ from it and fails on any difference. In a tree whose generated/ was left stale and
# not tested, the two can differ; nothing here can tell.
set(body "/* Generated from the shader sources in shaders/ by tools/inspect/embed_sources.cmake. */\n#include \"shadergen.h\"\n\n")
set(table "")
set(index 0)
foreach(name IN LISTS FILES)
  file(READ ${ROOT}/${name} hex HEX)
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
  string(REGEX REPLACE "(0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,)" "\\1\n" bytes "${bytes}")
  string(APPEND body "static const char source_${index}[] = {\n${bytes}0x00};\n\n")
  string(APPEND table "    {\"${name}\", source_${index}},\n")
  math(EXPR index "${index} + 1")
endforeach()
string(APPEND body "const sg_source cacao_inspect_sources[] = {\n${table}};\nconst size_t cacao_inspect_source_count = ${index};\n")
file(WRITE ${OUT}.tmp "${body}")
file(RENAME ${OUT}.tmp ${OUT})
