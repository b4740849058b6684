#ifndef signorini_contact_integration_rule_h
#define signorini_contact_integration_rule_h

#include <deal.II/base/quadrature.h>

#include <signorini/base/parameters.h>

#include <memory>

/**
 * Contact points on the slave surface (doc/theory.md section 6). A rule
 * gives, for one slave face, the points xi^e on the unit face and their
 * weights; the contact assembly evaluates the per-point law there. The fixed
 * rules (nodal, Gauss, Simpson, Newton-Cotes) return the same quadrature for
 * every face. The segment-based (mortar) rule depends on the master faces a
 * slave face overlaps at the current pairing: ContactProblem::segment
 * rebuilds the contact points of every face from segment_slave_face
 * (segmentation.h) and the law and the assembly are unchanged.
 */
namespace Signorini
{
  namespace Contact
  {
    using namespace dealii;

    template <int dim>
    class SlaveRule
    {
    public:
      virtual ~SlaveRule() = default;

      /**
       * Points and weights on the unit slave face number @p face_index
       * (the index into the contact problem's list of slave faces).
       */
      virtual const Quadrature<dim - 1> &
      face_quadrature(const unsigned int face_index) const = 0;

      /** true iff the points are the face nodes (diagonal psi-psi blocks). */
      virtual bool
      is_nodal() const = 0;

      /** Short description for the log, e.g. "gauss, 3 points per direction".
       */
      virtual std::string
      name() const = 0;
    };


    /** The nodal, Gauss, Simpson and Newton-Cotes rules. */
    template <int dim>
    class FixedRule : public SlaveRule<dim>
    {
    public:
      FixedRule(const IntegrationRule rule,
                const unsigned int    order,
                const unsigned int    fe_degree);

      const Quadrature<dim - 1> &
      face_quadrature(const unsigned int) const override
      {
        return quadrature;
      }

      bool
      is_nodal() const override
      {
        return nodal;
      }

      std::string
      name() const override
      {
        return description;
      }

    private:
      Quadrature<dim - 1> quadrature;
      bool                nodal;
      std::string         description;
    };
  } // namespace Contact
} // namespace Signorini

#endif
