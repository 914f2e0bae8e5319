#pragma once
// Report 445-1, Appendix A: the straight-blade formula of both Fortran programs, re-typed
// line for line in their units (RPM, blade length D1 in ft, masses in lb, speeds in
// ft/min, contact radius R in ft). The Fortran's pi is 3.1416; `pi` lets a test choose.
namespace j232::test {

inline double fortran_straight_va2(double RPM, double D1, double W2, double E, double VA1, double R, double W1, double pi = 3.1416) {
  const double CW1 = RPM * 2 * pi;
  const double VI = W2 * D1 * D1 / 3.0;
  const double VB1 = R * CW1;
  const double AX = VI / R + W1 * R;
  const double BX = VI * ((E * (VA1 + VB1)) / R);
  return (BX + VI * CW1 - W1 * VA1 * R) / AX;
}

}  // namespace j232::test
