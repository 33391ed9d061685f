# Real data shipped in the repository (data/openacc/*.tar.xz, JRC OpenACC, CC BY 4.0: see
# data/openacc/README.md), unpacked into the build tree at configure time with CMake's own
# archive support, so neither the build nor the tests read anything outside the repository.
# acc_unpack_bundled_data(NAME) sets ACC_DATA_<NAME>_DIR to the folder of the unpacked files.
function(acc_unpack_bundled_data name)
  set(archive ${PROJECT_SOURCE_DIR}/data/openacc/${name}.tar.xz)
  set(destination ${PROJECT_BINARY_DIR}/data/openacc/${name})
  set(stamp ${destination}/.unpacked_from_archive)
  # Unpack again whenever the archive changes (CMake re-runs when a configure dependency does).
  set_property(DIRECTORY ${PROJECT_SOURCE_DIR} APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${archive})
  file(SHA256 ${archive} archive_hash)
  set(unpacked_hash "")
  if(EXISTS ${stamp})
    file(READ ${stamp} unpacked_hash)
  endif()
  if(NOT unpacked_hash STREQUAL archive_hash)
    file(REMOVE_RECURSE ${destination})
    file(ARCHIVE_EXTRACT INPUT ${archive} DESTINATION ${destination})
    file(WRITE ${stamp} ${archive_hash})
  endif()
  string(TOUPPER ${name} upper_name)
  set(ACC_DATA_${upper_name}_DIR ${destination} PARENT_SCOPE)
endfunction()

acc_unpack_bundled_data(casale)
acc_unpack_bundled_data(zalazone_toyota_rav4_s)
acc_unpack_bundled_data(zalazone_dynamic)
