# Writes OUT: a C source defining `const char NAME[]` with the bytes of IN (zero-terminated), so
# cacao-inspect can show the shader source of this source tree at build time. That is the source
# the embedded table was built from when generated/ is current: a subset build generates its
# table from it in the same build, and the generated_reproduces test regenerates the checked-in
# generated/ from it and fails on any difference. In a tree whose generated/ was left stale and
# not tested, the two can differ; nothing here can tell.
file(READ ${IN} hex HEX)
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
string(REGEX REPLACE "(0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,)" "\\1\n" bytes "${bytes}")
file(WRITE ${OUT}.tmp "/* Generated from ${NAME_FOR_COMMENT} by embed.cmake. */\nconst char ${NAME}[] = {\n${bytes}0x00};\n")
file(RENAME ${OUT}.tmp ${OUT})
