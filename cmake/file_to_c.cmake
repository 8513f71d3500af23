# Embeds a text file (the GLSL source) in the library as a NUL-terminated char array NAME.
file(READ ${IN} hex HEX)
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
string(REGEX REPLACE "(0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,)" "\\1\n" bytes "${bytes}")
file(WRITE ${OUT} "/* Generated from ${NAME_OF_SOURCE} by cmake/file_to_c.cmake. Do not edit. */\n"
  "const char ${NAME}[] = {\n${bytes}0x00};\n")
