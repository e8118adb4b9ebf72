#pragma once
/// Normal pressure along the contact patch and the lumped-model factors that depend on it.
///
/// Deur Fig 7: a trapezoid rising from 0 at the leading edge (s = zeta/L = 0) to p_m at s = r_l,
/// flat to s = r_r, falling to 0 at s = 1; p_m = 2 / (1 + r_r - r_l) (eq 28). Uniform pressure is
/// the limit r_l = 0, r_r = 1 (p = 1).
///
/// kappa (eq 39) and lambda (eq 53) are ratios of integrals of the steady-state bristle deflection
/// z(s) = C (1 - exp(-y s)) (eq 23), y = L / Z (eqs 24, 31b). Deur's closed forms (eqs 40-41,
/// 43, 54, 57) subtract terms of size 1/y to leave O(1) results, which loses every digit as the slip
/// vanishes — the normal case of a car driving straight. We evaluate the defining integrals
/// exactly instead, from A_n(c) = int_0^c s^n (1 - exp(-y s)) ds by a power series for y c <= 2 and
/// the closed form beyond; the tests check the result against eqs 40, 43, 54, 57 and their limits
/// 42 and 55 where those are well conditioned.
#include <cmath>

#include "lane_keeping/common/scalar.h"

namespace lane_keeping {

class ContactPressure {
 public:
  static ContactPressure uniform() { return ContactPressure(0.0, 1.0); }
  static ContactPressure trapezoidal(double left_margin, double right_margin) {
    return ContactPressure(left_margin, right_margin);
  }

  double leftMargin() const { return r_l_; }
  double rightMargin() const { return r_r_; }
  bool isUniform() const { return r_l_ == 0.0 && r_r_ == 1.0; }
  /// p_m, Deur eq 28.
  double peak() const { return 2.0 / (1.0 + r_r_ - r_l_); }
  /// K_v = (2/L^2) int zeta p dzeta, Deur eq 31a.
  double kv() const { return peak() * (1.0 + r_r_ + r_r_ * r_r_ - r_l_ * r_l_) / 3.0; }
  /// Normalised pressure p(s), s = zeta / L in [0, 1]; integrates to 1.
  double at(double s) const {
    const double p_m = peak();
    if (s < 0.0 || s > 1.0) return 0.0;
    if (s < r_l_) return p_m * s / r_l_;
    if (s <= r_r_) return p_m;
    return p_m * (1.0 - s) / (1.0 - r_r_);
  }

  template <typename T>
  struct Factors {
    T kappa;
    T lambda;
  };

  /// kappa and lambda together (they share integrals). For uniform pressure, with the exponential
  /// phi-functions phi_k(y) = sum_n (-y)^n / (n + k)!, eq 39 reduces to kappa = phi1 / phi2 (= eq 43)
  /// and eq 53 to lambda = phi1 / (1 - 2 (1 + y) phi3) (= eq 57), both free of cancellation.
  template <typename T>
  [[gnu::always_inline]] Factors<T> factors(const T& y) const {
    if (toDouble(y) == 0.0) return {T(2.0 / kv()), T(lambdaMax())};
    if (!isUniform()) return {kappa(y), lambda(y)};
    if (toDouble(y) < kPolynomialLimit) {
      // Straight and gentle driving, the hot path: polynomial fits of eqs 43 and 57 on [0, 0.4]
      // (relative error < 3e-16 against 40-digit phi-functions; the test compares them with kappa()).
      return {polynomial(kKappaPolynomial, y), polynomial(kLambdaPolynomial, y)};
    }
    T phi1, phi2, phi3;
    phiFunctions(y, &phi1, &phi2, &phi3);
    if (toDouble(y) >= 1.0) {
      // 1 - 2 (1 + y) phi3 cancels to ~1/y for large y (relative error ~1e-16 y: lambda = inf from
      // y ~ 1e17). It equals (1 + 2 (exp(-y) - phi1) / y) / y (eq 57's denominator), which does not cancel.
      using std::exp;
      return {phi1 / phi2, phi1 * y / (1.0 + 2.0 * (exp(-y) - phi1) / y)};
    }
    return {phi1 / phi2, phi1 / (1.0 - 2.0 * (1.0 + y) * phi3)};
  }

  /// phi_1, phi_2, phi_3 of y >= 0: power series below y = 1, the recurrence
  /// phi_(k+1) = (1/k! - phi_k) / y from phi_0 = exp(-y) above.
  template <typename T>
  static void phiFunctions(const T& y, T* phi1, T* phi2, T* phi3) {
    using std::exp;
    if (toDouble(y) < 1.0) {
      // phi_k = sum_n (-y)^n / (n + k)!; stops once a term of phi_1 is below 1e-17 of phi_3 (~1/6).
      T power(1.0);
      *phi1 = T(kInverseFactorial[1]);
      *phi2 = T(kInverseFactorial[2]);
      *phi3 = T(kInverseFactorial[3]);
      for (int n = 1; n + 3 < kFactorials; ++n) {
        power = power * (-y);
        *phi1 = *phi1 + power * kInverseFactorial[n + 1];
        *phi2 = *phi2 + power * kInverseFactorial[n + 2];
        *phi3 = *phi3 + power * kInverseFactorial[n + 3];
        if (std::fabs(toDouble(power)) * kInverseFactorial[n + 1] <= 1e-17 * (1.0 / 6.0)) break;
      }
      return;
    }
    const T e0 = exp(-y);
    *phi1 = (1.0 - e0) / y;
    *phi2 = (1.0 - *phi1) / y;
    *phi3 = (0.5 - *phi2) / y;
  }

  /// kappa = S / z~ in steady state (Deur eq 39), y = L / Z >= 0. kappa(0) = 2 / K_v (eq 42b).
  template <typename T>
  T kappa(const T& y) const {
    if (toDouble(y) == 0.0) return T(2.0 / kv());
    const T head = r_l_ > 0.0 ? T(A(0, r_l_, y) / r_l_) : T(0.0);                  // mean of e over [0, r_l]
    const T tail = r_r_ < 1.0 ? T((A(0, 1.0, y) - A(0, r_r_, y)) / (1.0 - r_r_)) : e(1.0, y);  // over [r_r, 1]
    return peak() * (tail - head) / weighted(0, y);
  }

  /// lambda = S* / psi in steady state (Deur eq 53). lambda(0) = Deur eq 55b.
  template <typename T>
  T lambda(const T& y) const {
    if (toDouble(y) == 0.0) return T(lambdaMax());
    const T head = r_l_ > 0.0 ? T(A(1, r_l_, y) / r_l_) : T(0.0);  // mean of s e over [0, r_l]
    const T tail = r_r_ < 1.0 ? T((A(1, 1.0, y) - A(1, r_r_, y)) / (1.0 - r_r_)) : e(1.0, y);
    return peak() * (tail - head) / (2.0 * weighted(1, y));
  }

  /// Deur eq 55b.
  double lambdaMax() const {
    return 1.5 * ((r_r_ * r_r_ + r_r_ + 1.0 - r_l_ * r_l_) / 3.0) /
           ((r_r_ * r_r_ * r_r_ + r_r_ * r_r_ + r_r_ + 1.0 - r_l_ * r_l_ * r_l_) / 4.0);
  }

  /// e(s) = 1 - exp(-y s), accurate for small y s.
  template <typename T>
  static T e(double s, const T& y) {
    using std::exp;
    const T x = y * s;
    const double xv = toDouble(x);
    if (xv < 0.5) {
      // x - x^2/2! + x^3/3! - ...; stops once a term is below 1e-17 of the sum.
      T term = x;
      T sum = x;
      for (int m = 2; m < kSeriesTerms; ++m) {
        term = term * (-x) * kReciprocal[m];
        sum = sum + term;
        if (std::fabs(toDouble(term)) <= 1e-17 * std::fabs(toDouble(sum))) break;
      }
      return sum;
    }
    return 1.0 - exp(-x);
  }

  /// A_n(c) = int_0^c s^n (1 - exp(-y s)) ds, n in {0, 1, 2}.
  template <typename T>
  static T A(int n, double c, const T& y) {
    using std::exp;
    if (c <= 0.0) return T(0.0);
    const T x = y * c;
    const double cn1 = std::pow(c, n + 1);
    if (toDouble(x) <= 2.0) {
      // c^(n+1) sum_{m>=1} (-1)^(m+1) x^m / (m! (m+n+1)); 2^31/31! ~ 1e-25 bounds the tail.
      T power = x;  // (-1)^(m+1) x^m / m!
      T sum = power * kReciprocal[n + 2];
      for (int m = 2; m < kSeriesTerms; ++m) {
        power = power * (-x) * kReciprocal[m];
        const T term = power * kReciprocal[m + n + 1];
        sum = sum + term;
        if (std::fabs(toDouble(term)) <= 1e-17 * std::fabs(toDouble(sum))) break;
      }
      return cn1 * sum;
    }
    const T ex = exp(-x);
    T b;  // int_0^c s^n exp(-y s) ds
    if (n == 0) {
      b = (1.0 - ex) / y;
    } else if (n == 1) {
      b = (1.0 - ex * (1.0 + x)) / (y * y);
    } else {
      // (ex x) x, not ex x^2: x^2 overflows for y c > 1e154 and 0 * inf would give NaN.
      b = (2.0 - ex * (2.0 + 2.0 * x) - (ex * x) * x) / (y * y * y);
    }
    return cn1 / static_cast<double>(n + 1) - b;
  }

 private:
  /// Polynomials of degree 8 for kappa(y) = phi1/phi2 and lambda(y) = phi1/(1 - 2 (1 + y) phi3)
  /// (uniform pressure) on [0, 0.4]: interpolation at the 9 Chebyshev points in 40-digit arithmetic,
  /// by scripts/fit_factor_polynomials.py, which also measures the largest relative error in double
  /// against the exact functions: 2.1e-16 (kappa) and 2.8e-16 (lambda). kappa(0) = 2 (eq 42b) and
  /// lambda(0) = 3/2 (eq 55b) come out exact. (The degree-13 Taylor polynomials used before reached
  /// the same accuracy with 5 more terms each.)
  static constexpr double kPolynomialLimit = 0.4;
  static constexpr int kPolynomialTerms = 9;
  static constexpr double kKappaPolynomial[kPolynomialTerms] = {
      2.0, -0.33333333333334014, 0.05555555555601115, -0.0037037037154756805, -0.00030864182232211656,
      7.348506125079241e-05, -4.850166873408932e-07, -1.1557509130978062e-06, 1.0677136681201585e-07};
  static constexpr double kLambdaPolynomial[kPolynomialTerms] = {
      1.5, -0.187500000000008, 0.029687500000532805, -0.0013671875136957844, -0.0002448379931329037,
      3.095226404582052e-05, 2.343444811373726e-06, -6.288528658504305e-07, 8.907485695264528e-09};
  /// Estrin's scheme: pairs, then powers y^2, y^4, y^8 — a dependency chain of depth 4 instead of
  /// Horner's 8.
  template <typename T>
  static T polynomial(const double (&c)[kPolynomialTerms], const T& y) {
    static_assert(kPolynomialTerms == 9, "the scheme below is written out for degree 8");
    const T y2 = y * y;
    const T y4 = y2 * y2;
    const T y8 = y4 * y4;
    const T a0 = c[0] + c[1] * y, a1 = c[2] + c[3] * y, a2 = c[4] + c[5] * y, a3 = c[6] + c[7] * y;
    return (a0 + a1 * y2) + (a2 + a3 * y2) * y4 + c[8] * y8;
  }

  static constexpr int kFactorials = 24;
  /// 1/n!, n = 0..23 (23!^-1 ~ 4e-23: the phi series for y < 1 ends well before).
  static constexpr double kInverseFactorial[kFactorials] = {
      1.0, 1.0, 1.0 / 2, 1.0 / 6, 1.0 / 24, 1.0 / 120, 1.0 / 720, 1.0 / 5040, 1.0 / 40320, 1.0 / 362880,
      1.0 / 3628800, 1.0 / 39916800, 1.0 / 479001600, 1.0 / 6227020800.0, 1.0 / 87178291200.0,
      1.0 / 1307674368000.0, 1.0 / 20922789888000.0, 1.0 / 355687428096000.0, 1.0 / 6402373705728000.0,
      1.0 / 121645100408832000.0, 1.0 / 2432902008176640000.0, 1.0 / 51090942171709440000.0,
      1.0 / 1124000727777607680000.0, 1.0 / 25852016738884976640000.0};
  static constexpr int kSeriesTerms = 32;
  /// kReciprocal[m] = 1/m (index 0 unused): multiplications instead of divisions in the series.
  static constexpr double kReciprocal[kSeriesTerms + 4] = {
      0.0,       1.0,       1.0 / 2,   1.0 / 3,   1.0 / 4,   1.0 / 5,   1.0 / 6,   1.0 / 7,   1.0 / 8,
      1.0 / 9,   1.0 / 10,  1.0 / 11,  1.0 / 12,  1.0 / 13,  1.0 / 14,  1.0 / 15,  1.0 / 16,  1.0 / 17,
      1.0 / 18,  1.0 / 19,  1.0 / 20,  1.0 / 21,  1.0 / 22,  1.0 / 23,  1.0 / 24,  1.0 / 25,  1.0 / 26,
      1.0 / 27,  1.0 / 28,  1.0 / 29,  1.0 / 30,  1.0 / 31,  1.0 / 32,  1.0 / 33,  1.0 / 34,  1.0 / 35};

  ContactPressure(double left_margin, double right_margin) : r_l_(left_margin), r_r_(right_margin) {}

  /// int_0^1 s^n e(s) p(s) ds over the three pieces of the trapezoid.
  template <typename T>
  T weighted(int n, const T& y) const {
    const double p_m = peak();
    T total = p_m * (A(n, r_r_, y) - A(n, r_l_, y));
    if (r_l_ > 0.0) total = total + (p_m / r_l_) * A(n + 1, r_l_, y);
    if (r_r_ < 1.0) {
      total = total + (p_m / (1.0 - r_r_)) * ((A(n, 1.0, y) - A(n, r_r_, y)) - (A(n + 1, 1.0, y) - A(n + 1, r_r_, y)));
    }
    return total;
  }

  double r_l_;
  double r_r_;
};

}  // namespace lane_keeping
