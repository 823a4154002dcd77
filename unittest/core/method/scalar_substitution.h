// The one-variable example of the method (doc/theory.rst, "The SISSM split"): successive substitution for x = g(x), plain and with an
// implicit (SISSM-split) linear term (doc/theory.rst).

#ifndef PERISISSM_SCALAR_SUBSTITUTION_H
#define PERISISSM_SCALAR_SUBSTITUTION_H

#include <functional>
#include <vector>

namespace PeriSISSM {

using ScalarMap = std::function<double(double)>;

// Successive substitution x_{k+1} = g(x_k).
//
// Inputs:  g the map, x0 start value, n number of iterations (>= 0).
// Outputs: the n + 1 iterates x_0 .. x_n.
std::vector<double> iterate(const ScalarMap &g, double x0, int n);

// The split map of x = g(x) with implicit coefficient a >= 0.
//
// Writing g(x) = (g(x) + a x) - a x and taking the -a x term at the new iterate,
// x_{k+1} = g(x_k) + a x_k - a x_{k+1}, gives x_{k+1} = (g(x_k) + a x_k) / (1 + a): the same
// fixed points as g, with slope (g'(x) + a)/(1 + a). This is the scalar form of the particle
// update (rho + h^2 c) y_{k+1} = rho yhat + h^2 (f(y_k) + c y_k).
//
// Inputs:  g the map, a implicit coefficient (>= 0; minus the slope of the linear term of g).
// Outputs: the map x -> (g(x) + a x) / (1 + a).
ScalarMap split_map(ScalarMap g, double a);

// The method's one-variable example g(x) = (x - 2)^2 = x^2 - 4x + 4, fixed points 1 and 4.
//
// Inputs:  x.  Outputs: (x - 2)^2.
double talk_example_map(double x);

// Implicit coefficient of the example: the term -4x of g has negative slope; it goes
// to the left-hand side, a = 4, and the split map is (x^2 + 4)/5.
constexpr double kTalkExampleImplicit = 4.0;

}    // namespace PeriSISSM

#endif    // PERISISSM_SCALAR_SUBSTITUTION_H
