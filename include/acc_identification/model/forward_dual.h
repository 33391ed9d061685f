#pragma once

#include <array>
#include <cmath>
#include <cstddef>

namespace acc
{
/// A number with its derivatives with respect to up to N parameters (forward-mode automatic
/// differentiation). The follower simulator is written once, as a template over its scalar type:
/// with double it is the simulator, with ForwardDual it also carries the exact sensitivities of
/// every state to every parameter, whatever effects are switched on. The value part of each
/// operation is the very double operation of the plain simulator, so values agree bit for bit.
/// N is a compile-time capacity (fixed-size loops the compiler vectorises); unused slots stay 0.
template <std::size_t N>
struct ForwardDual
{
  double value = 0.0;
  std::array<double, N> derivative{};

  ForwardDual() = default;
  /// A constant: every derivative 0.
  ForwardDual(double constant) : value(constant) {}  // NOLINT: constants mix freely with duals
  /// The parameter number `index` itself (derivative 1 with respect to it).
  static ForwardDual parameter(double value, std::size_t index)
  {
    ForwardDual x(value);
    x.derivative[index] = 1.0;
    return x;
  }
};

inline double valueOf(double x) { return x; }
template <std::size_t N>
double valueOf(const ForwardDual<N>& x)
{
  return x.value;
}

template <std::size_t N>
ForwardDual<N> operator+(const ForwardDual<N>& a, const ForwardDual<N>& b)
{
  ForwardDual<N> r(a.value + b.value);
  for (std::size_t i = 0; i < N; ++i)
    r.derivative[i] = a.derivative[i] + b.derivative[i];
  return r;
}

template <std::size_t N>
ForwardDual<N> operator-(const ForwardDual<N>& a, const ForwardDual<N>& b)
{
  ForwardDual<N> r(a.value - b.value);
  for (std::size_t i = 0; i < N; ++i)
    r.derivative[i] = a.derivative[i] - b.derivative[i];
  return r;
}

template <std::size_t N>
ForwardDual<N> operator-(const ForwardDual<N>& a)
{
  ForwardDual<N> r(-a.value);
  for (std::size_t i = 0; i < N; ++i)
    r.derivative[i] = -a.derivative[i];
  return r;
}

template <std::size_t N>
ForwardDual<N> operator*(const ForwardDual<N>& a, const ForwardDual<N>& b)
{
  ForwardDual<N> r(a.value * b.value);
  for (std::size_t i = 0; i < N; ++i)
    r.derivative[i] = a.derivative[i] * b.value + a.value * b.derivative[i];
  return r;
}

template <std::size_t N>
ForwardDual<N> operator/(const ForwardDual<N>& a, const ForwardDual<N>& b)
{
  ForwardDual<N> r(a.value / b.value);
  const double inverse_square = 1.0 / (b.value * b.value);
  for (std::size_t i = 0; i < N; ++i)
    r.derivative[i] = (a.derivative[i] * b.value - a.value * b.derivative[i]) * inverse_square;
  return r;
}

// Mixed forms: a double is a constant, so these skip the work of a zero derivative.
template <std::size_t N>
ForwardDual<N> operator+(const ForwardDual<N>& a, double b)
{
  ForwardDual<N> r = a;
  r.value = a.value + b;
  return r;
}
template <std::size_t N>
ForwardDual<N> operator+(double a, const ForwardDual<N>& b)
{
  ForwardDual<N> r = b;
  r.value = a + b.value;
  return r;
}
template <std::size_t N>
ForwardDual<N> operator-(const ForwardDual<N>& a, double b)
{
  ForwardDual<N> r = a;
  r.value = a.value - b;
  return r;
}
template <std::size_t N>
ForwardDual<N> operator-(double a, const ForwardDual<N>& b)
{
  ForwardDual<N> r(a - b.value);
  for (std::size_t i = 0; i < N; ++i)
    r.derivative[i] = -b.derivative[i];
  return r;
}
template <std::size_t N>
ForwardDual<N> operator*(const ForwardDual<N>& a, double b)
{
  ForwardDual<N> r(a.value * b);
  for (std::size_t i = 0; i < N; ++i)
    r.derivative[i] = a.derivative[i] * b;
  return r;
}
template <std::size_t N>
ForwardDual<N> operator*(double a, const ForwardDual<N>& b)
{
  ForwardDual<N> r(a * b.value);
  for (std::size_t i = 0; i < N; ++i)
    r.derivative[i] = a * b.derivative[i];
  return r;
}
template <std::size_t N>
ForwardDual<N> operator/(const ForwardDual<N>& a, double b)
{
  ForwardDual<N> r(a.value / b);
  for (std::size_t i = 0; i < N; ++i)
    r.derivative[i] = a.derivative[i] / b;
  return r;
}
template <std::size_t N>
ForwardDual<N> operator/(double a, const ForwardDual<N>& b)
{
  return ForwardDual<N>(a) / b;
}

template <std::size_t N>
ForwardDual<N>& operator+=(ForwardDual<N>& a, const ForwardDual<N>& b)
{
  a = a + b;
  return a;
}

template <std::size_t N>
ForwardDual<N> exp(const ForwardDual<N>& a)
{
  const double e = std::exp(a.value);
  ForwardDual<N> r(e);
  for (std::size_t i = 0; i < N; ++i)
    r.derivative[i] = e * a.derivative[i];
  return r;
}

}  // namespace acc
