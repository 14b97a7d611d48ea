#pragma once
// The sampling grid (docs/conventions.md §Grid): nx × ny samples over a periodic patch lx × ly
// metres; sample (i, j) at (i lx/nx, j ly/ny); row-major, x fastest. Wave number index n of
// array index i is i for i < nx/2 and i − nx otherwise (FFT order), so n ∈ [−nx/2, nx/2) and
// kx = 2π n / lx.
namespace swell::reference {

struct Grid {
  int nx = 0, ny = 0;
  double lx = 0, ly = 0;  // metres

  static Grid create(int nx, int ny, double lx, double ly);  // validates; throws InvalidInput

  double dkx() const;  // 2π/lx, rad/m
  double dky() const;
  // Signed wave-number index of array index i along an axis of n samples.
  static int signed_index(int i, int n) { return i < (n + 1) / 2 ? i : i - n; }
  // The Nyquist index −n/2 exists only for even n; it carries no energy.
  static bool is_nyquist(int signed_index, int n) { return n % 2 == 0 && signed_index == -n / 2; }
  // True for the wave vectors that carry energy: not k = 0, not the Nyquist row or column.
  bool carries_energy(int n, int m) const {
    return !(n == 0 && m == 0) && !is_nyquist(n, nx) && !is_nyquist(m, ny);
  }
};

}  // namespace swell::reference
