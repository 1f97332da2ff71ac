#pragma once
// How FFTW plans the pressure and Helmholtz transforms (the case key solver.fft_planning).
namespace eulerfsi {

// Estimate: algorithms chosen by heuristics, the same in every process and run.
// Measure: FFTW times candidate algorithms when a solver is built and keeps the fastest; the choice
//   can differ between processes, so results differ from Estimate's (and between runs) in the last
//   bits; a restart reuses the stored choices (poisson/fft_wisdom.hpp).
// WisdomOnly: Measure's plans taken from imported wisdom only; building a solver fails where the
//   wisdom lacks a plan. Not a case-file value: it checks that stored wisdom is complete.
enum class FftPlanning { Estimate, Measure, WisdomOnly };

}  // namespace eulerfsi
