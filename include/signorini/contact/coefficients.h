#ifndef signorini_contact_coefficients_h
#define signorini_contact_coefficients_h

#include <signorini/base/parameters.h>
#include <signorini/contact/contact_law.h>

#include <vector>

namespace Signorini
{
  namespace Contact
  {
    /**
     * The augmentation coefficients of the contact pairs (theory.md F8,
     * "magic coefficients") and the law parameters of a pair:
     * - rho_n = c_n E / h, with h the mean slave face size and E the
     *   softer body's representative modulus (the slave's, or a meshed
     *   master's if it is softer: a gap error is resisted by the softer
     *   body, and rho_n from a stiff slave on a soft master would weigh the
     *   gap 1/contrast too much);
     * - rho_t = c_t rho_n / (mu p_ref), which makes the tangential
     *   stiffness mu p_ref rho_t of a sticking point comparable to rho_n;
     *   p_ref is the RMS of the nodal pressures in contact
     *   (set_pressure_level()), 1e-3 E before any is known.
     * The rows of the multiplier equations are scaled by rho_n (lambda)
     * and rho_t (Lambda) of their pair.
     */
    class Coefficients
    {
    public:
      explicit Coefficients(const ContactParameters &contact);

      /** Per pair: the mean slave face size h [m] and the representative
       * moduli of the slave and of a meshed master (0: rigid) [Pa]. */
      void
      set(const std::vector<double> &face_size,
          const std::vector<double> &slave_modulus,
          const std::vector<double> &master_modulus);

      /** p_ref = @p rms_pressure [Pa] for frictional pair @p p, and its
       * rho_t. */
      void
      set_pressure_level(const unsigned int p, const double rms_pressure);

      /** rho_n of pair @p p [Pa/m]. */
      double
      normal(const unsigned int p) const
      {
        return rho_n[p];
      }
      /** rho_t of pair @p p [1/m] (1 for a frictionless pair). */
      double
      tangential(const unsigned int p) const
      {
        return rho_t[p];
      }

      /** The contact law's parameters for pair @p p: rho_n, rho_t, mu,
       * the zero threshold 1e-12 E and the weight of inactive friction. */
      LawParameters
      law(const unsigned int p) const;

    private:
      const ContactParameters &contact;
      std::vector<double>      rho_n, rho_t, p_ref, modulus; // per pair
    };
  } // namespace Contact
} // namespace Signorini

#endif
