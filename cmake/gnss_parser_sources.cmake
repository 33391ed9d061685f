# The NMEA parser, line and epoch assembly of the gnss component: pure functions on bytes, built
# into acc_gnss and, with clang's libFuzzer and sanitizers, into the fuzzer
# (scripts/test_hooks/fuzz_nmea.sh configures test/fuzz/CMakeLists.txt, which includes this file).
set(ACC_GNSS_PARSER_SOURCES
  src/gnss/nmea_fields.cpp
  src/gnss/nmea_parser.cpp
  src/gnss/nmea_writer.cpp
  src/gnss/nmea_statistics.cpp
  src/gnss/utc_date.cpp
  src/gnss/gnss_epoch_assembler.cpp
  src/gnss/gnss_velocity.cpp
  src/gnss/nmea_decoder.cpp)
