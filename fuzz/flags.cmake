# Included by the top-level CMakeLists.txt when ENDATSIM_FUZZ is on, before any target exists:
# every project library is built with libFuzzer coverage, AddressSanitizer and UBSan, so the
# fuzz targets see coverage inside the loader, the line and the encoder.
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "ENDATSIM_FUZZ needs clang: configure with -DCMAKE_CXX_COMPILER=clang++")
endif()
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -gline-tables-only)
add_link_options(-fsanitize=address,undefined)
