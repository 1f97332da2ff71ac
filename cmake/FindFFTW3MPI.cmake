# Finds FFTW3 (double) and its MPI library; defines FFTW3::fftw3_mpi.
find_path(FFTW3_INCLUDE_DIR fftw3-mpi.h HINTS $ENV{FFTW_ROOT}/include ${FFTW_ROOT}/include)
find_library(FFTW3_LIBRARY fftw3 HINTS $ENV{FFTW_ROOT}/lib ${FFTW_ROOT}/lib)
find_library(FFTW3_MPI_LIBRARY fftw3_mpi HINTS $ENV{FFTW_ROOT}/lib ${FFTW_ROOT}/lib)
# optional: FFTW's OpenMP threads, so the Poisson solve uses the cores Kokkos uses
find_library(FFTW3_OMP_LIBRARY fftw3_omp HINTS $ENV{FFTW_ROOT}/lib ${FFTW_ROOT}/lib)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(FFTW3MPI
  REQUIRED_VARS FFTW3_MPI_LIBRARY FFTW3_LIBRARY FFTW3_INCLUDE_DIR
  FAIL_MESSAGE "FFTW3 with its MPI library not found (set FFTW_ROOT). On Debian: apt-get install libfftw3-dev libfftw3-mpi-dev")
if(FFTW3MPI_FOUND AND NOT TARGET FFTW3::fftw3_mpi)
  add_library(FFTW3::fftw3_mpi INTERFACE IMPORTED)
  set_target_properties(FFTW3::fftw3_mpi PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${FFTW3_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${FFTW3_MPI_LIBRARY};${FFTW3_LIBRARY};MPI::MPI_C")
endif()
