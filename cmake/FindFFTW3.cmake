# Finds serial FFTW3 (double); defines FFTW3::fftw3 (and FFTW3_OMP_LIBRARY when FFTW has OpenMP threads).
find_path(FFTW3_INCLUDE_DIR fftw3.h HINTS $ENV{FFTW_ROOT}/include ${FFTW_ROOT}/include)
find_library(FFTW3_LIBRARY fftw3 HINTS $ENV{FFTW_ROOT}/lib ${FFTW_ROOT}/lib)
find_library(FFTW3_OMP_LIBRARY fftw3_omp HINTS $ENV{FFTW_ROOT}/lib ${FFTW_ROOT}/lib)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(FFTW3
  REQUIRED_VARS FFTW3_LIBRARY FFTW3_INCLUDE_DIR
  FAIL_MESSAGE "FFTW3 not found (set FFTW_ROOT). On Debian: apt-get install libfftw3-dev")
if(FFTW3_FOUND AND NOT TARGET FFTW3::fftw3)
  add_library(FFTW3::fftw3 INTERFACE IMPORTED)
  set_target_properties(FFTW3::fftw3 PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${FFTW3_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${FFTW3_LIBRARY}")
endif()
