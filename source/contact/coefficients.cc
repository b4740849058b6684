// The augmentation coefficients of the contact pairs.
#include <signorini/contact/coefficients.h>

#include <algorithm>

namespace Signorini
{
  namespace Contact
  {
    Coefficients::Coefficients(const ContactParameters &contact)
        : contact(contact)
    {
    }


    void
    Coefficients::set(const std::vector<double> &face_size,
                      const std::vector<double> &slave_modulus,
                      const std::vector<double> &master_modulus)
    {
      const auto        &pairs   = contact.pairs;
      const unsigned int n_pairs = pairs.size();
      rho_n.assign(n_pairs, 0.);
      rho_t.assign(n_pairs, 1.);
      p_ref.assign(n_pairs, 0.);
      modulus = slave_modulus;
      for (unsigned int p = 0; p < n_pairs; ++p)
        {
          const double E  = slave_modulus[p];
          const double Em = master_modulus[p];
          rho_n[p] = pairs[p].rho_n_factor * (Em > 0 ? std::min(E, Em) : E) /
                     face_size[p];
          p_ref[p] = 1e-3 * E;
          if (pairs[p].friction > 0)
            rho_t[p] =
              pairs[p].rho_t_factor * rho_n[p] / (pairs[p].friction * p_ref[p]);
        }
    }


    void
    Coefficients::set_pressure_level(const unsigned int p,
                                     const double       rms_pressure)
    {
      const auto &pair = contact.pairs[p];
      if (pair.friction == 0)
        return;
      p_ref[p] = rms_pressure;
      rho_t[p] = pair.rho_t_factor * rho_n[p] / (pair.friction * p_ref[p]);
    }


    LawParameters
    Coefficients::law(const unsigned int p) const
    {
      LawParameters law;
      law.rho_n          = rho_n[p];
      law.rho_t          = rho_t[p];
      law.mu             = contact.pairs[p].friction;
      law.zero_threshold = 1e-12 * modulus[p];
      if (law.mu > 0)
        {
          // Friction law of a point with inactive friction, weighted like
          // an active point at 1e-4 of the pressure level: unit invariant,
          // and small enough that a node at the contact edge (mortar and
          // Gauss rules mix free and active points in its Lambda row)
          // follows its active points. See doc/robustness.md for the sweep
          // of the factor.
          constexpr double free_weight = 1e-4;
          law.free_friction_scale = free_weight * law.mu * p_ref[p] / rho_t[p];
        }
      return law;
    }
  } // namespace Contact
} // namespace Signorini
