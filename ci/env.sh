# Sourced by the ci/ scripts: where Kokkos is, how MPI may run here.
deps_dir=${EULERFSI_DEPS:-$HOME/.cache/eulerfsi}
# EULERFSI_KOKKOS4=1: the Kokkos 4.6 that `ci/setup --kokkos4` builds (it overrides KOKKOS_ROOT)
if [ "${EULERFSI_KOKKOS4:-0}" = 1 ]; then
  export KOKKOS_ROOT="$deps_dir/kokkos-4.6-openmp"
elif [ -z "${KOKKOS_ROOT:-}" ]; then
  export KOKKOS_ROOT="$deps_dir/kokkos-3.4.1-openmp"
fi
# Open MPI refuses root and more ranks than cores unless told otherwise.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-2}
export OMP_PROC_BIND=${OMP_PROC_BIND:-false}
