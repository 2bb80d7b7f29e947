# Turns a file of little-endian uint16 values into a C++ source defining them as an array, so
# generated data lives in data/ as data and only becomes code in the build directory.
#   cmake -DINPUT=f.u16 -DOUTPUT=f.cpp -DSYMBOL=ns::name -DHEADER=dir/h.h -P embed_u16.cmake
# The byte order is fixed by the file format, not by the host, so the array is the same anywhere.
foreach(var INPUT OUTPUT SYMBOL HEADER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "embed_u16.cmake: -D${var}=... missing")
  endif()
endforeach()

file(READ "${INPUT}" hex HEX)
string(LENGTH "${hex}" digits)
math(EXPR remainder "${digits} % 4")
if(digits EQUAL 0 OR NOT remainder EQUAL 0)
  message(FATAL_ERROR "embed_u16.cmake: ${INPUT} is not a whole number of uint16 values")
endif()
math(EXPR count "${digits} / 4")
# Each pair of bytes, low byte first, becomes one 0xHHLL literal; 16 literals to a line.
string(REGEX REPLACE "(..)(..)" "0x\\2\\1," values "${hex}")
string(REPEAT "0x....," 16 line)
string(REGEX REPLACE "(${line})" "\\1\n" values "${values}")
string(REGEX MATCH "^(.*)::([^:]+)$" unused "${SYMBOL}")
set(namespace "${CMAKE_MATCH_1}")
set(name "${CMAKE_MATCH_2}")

file(WRITE "${OUTPUT}"
  "// Generated at build time by cmake/embed_u16.cmake from ${INPUT}. Do not edit.\n"
  "#include \"${HEADER}\"\n\n"
  "namespace ${namespace} {\n"
  "const uint16_t ${name}[${count}] = {\n${values}};\n"
  "}  // namespace ${namespace}\n")
