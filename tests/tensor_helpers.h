// Helpers of the constitutive-model unit tests (tests/neo_hookean.cc,
// tests/j2_finite_strain.cc): random tensors, rotations, verdicts.
#ifndef signorini_tests_tensor_helpers_h
#define signorini_tests_tensor_helpers_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <cmath>
#include <random>

namespace test_helpers
{
  using namespace dealii;

  /** A 3 x 3 tensor with entries uniform in [-scale, scale]. */
  inline Tensor<2, 3>
  random_tensor(std::mt19937 &rng, const double scale)
  {
    std::uniform_real_distribution<double> u(-1, 1);
    Tensor<2, 3>                           t;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        t[i][j] = scale * u(rng);
    return t;
  }

  /** A rotation by @p angle about the unit axis @p a (Rodrigues). */
  inline Tensor<2, 3>
  rotation(const Tensor<1, 3> &a, const double angle)
  {
    Tensor<2, 3> K;
    K[0][1] = -a[2];
    K[0][2] = a[1];
    K[1][2] = -a[0];
    K[1][0] = a[2];
    K[2][0] = -a[1];
    K[2][1] = a[0];
    return Tensor<2, 3>(unit_symmetric_tensor<3>()) + std::sin(angle) * K +
           (1 - std::cos(angle)) * K * K;
  }

  /** A rotation by @p angle about the z axis. */
  inline Tensor<2, 3>
  rotation_z(const double angle)
  {
    Tensor<1, 3> e3;
    e3[2] = 1;
    return rotation(e3, angle);
  }

  inline const char *
  verdict(const bool ok)
  {
    return ok ? "PASS" : "FAIL";
  }
} // namespace test_helpers

#endif
