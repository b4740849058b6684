#ifndef signorini_contact_contact_law_h
#define signorini_contact_contact_law_h

#include <deal.II/base/tensor.h>

#include <array>
#include <optional>
#include <vector>

namespace Signorini
{
  namespace Contact
  {
    using namespace dealii;

    /**
     * Status of one contact point, see doc/theory.md sections 3.1 and 3.2.
     *
     * A point is `free` iff it is not in contact. An in-contact point is
     * `stick` or `slip` according to the friction test |h| <= 1 of section
     * 3.2. Points without an active friction law (mu == 0, or a zero friction
     * threshold, section 3.3) offer no tangential resistance and are reported
     * as `slip`; PointResponse::friction_active tells the two cases apart.
     */
    enum class PointStatus
    {
      free,
      stick,
      slip
    };

    /**
     * Human-readable name of a status ("free", "stick", "slip"), for logs.
     */
    const char *
    to_string(const PointStatus status);


    /**
     * Coefficients of the augmented Lagrangian contact law (doc/theory.md
     * sections 3 and 4). Units assume lambda is a pressure [Pa] and
     * displacements are in [m]. They are expected to be validated where they
     * are parsed; evaluate_contact_law() only checks them in debug mode.
     */
    struct LawParameters
    {
      /**
       * Normal augmentation coefficient rho_n [Pa/m], > 0.
       */
      double rho_n;

      /**
       * Tangential augmentation coefficient rho_t [1/m], > 0 (Lambda is
       * dimensionless, so rho_t v must be). Only used if mu > 0.
       */
      double rho_t;

      /**
       * Coulomb coefficient mu [-], >= 0. mu == 0 means frictionless: every
       * friction density and derivative is zero and the assembly must not
       * create Lambda rows at all (section 4, last paragraph).
       */
      double mu;

      /**
       * |lambda_f| at or below this value [Pa] counts as a zero friction
       * threshold (section 3.3). A point that closed in the last solve has
       * lambda_f = 0 only up to the round-off of that solve; treating that
       * round-off as a threshold would give a Lambda block of size 1e-20.
       * ContactProblem uses 1e-12 E. Default: exact zero.
       */
      double zero_threshold = 0.;

      /**
       * Weight of the friction law of a point whose friction is inactive
       * (free, or closed with a zero threshold): its Lambda row is
       * free_friction_scale * Lambda [Pa m], so that it has the units of
       * the active rows, (mu lambda_f / rho_t)(T Lambda - P_B(h)).
       * ContactProblem uses 1e-4 mu p_ref / rho_t, with p_ref the pressure
       * level of rho_t. With weight 1 (theory.md F4 as written) the
       * mixture of free and active points in one node's Lambda row
       * (mortar, Gauss) depends on the unit system. Default 1.
       */
      double free_friction_scale = 1.;
    };


    /**
     * Everything known at one contact point for the current Newton iterate
     * (doc/theory.md section 2); pairing, n and T are frozen inside a
     * geometric iteration.
     */
    template <int dim>
    struct PointState
    {
      /**
       * Unit normal n of the master surface, pointing into the master body.
       */
      Tensor<1, dim> normal;

      /**
       * Orthonormal tangent basis tau_k (columns of T), orthogonal to n.
       * Lambda is expressed in this basis. See tangent_basis().
       */
      std::array<Tensor<1, dim>, dim - 1> tangents;

      /**
       * Gap g [m] at the current iterate, g_0 included; g > 0 means
       * interpenetration.
       */
      double gap;

      /**
       * Slip increment v = P (Delta u^e - Delta u^m) [m] at the current
       * iterate (a tangent vector).
       */
      Tensor<1, dim> slip;

      /**
       * Contact multiplier lambda [Pa] at the point, <= 0 in compression.
       */
      double lambda;

      /**
       * The threshold lambda_f [Pa] that weights the friction law's rows,
       * (mu lambda_f / rho_t)(T Lambda - P_B(h)): lambda at the Newton
       * iterate (doc/theory.md section 3.2, "Row weight of the friction
       * law"). A weight, not an unknown of the law: the rows have no
       * derivative in lambda through it. Their solution (stick: v = 0;
       * slip: T Lambda = q) does not depend on it. The traction
       * mu lambda_f P_B(h) takes lambda itself. Ignored if mu == 0.
       */
      double row_lambda = 0.;

      /**
       * Friction semi-multiplier Lambda [-] in tangent coordinates. Ignored if
       * mu == 0.
       */
      Tensor<1, dim - 1> Lambda;

      /**
       * Q, the projector onto the tangents a Dirichlet condition holds at
       * the point's nodes, in tangent coordinates (theory.md F8); zero
       * where nothing is held. Sticking, the rows along them are
       * free_friction_scale Q Lambda (Lambda = 0 there: the support
       * carries the force) and the traction leaves out their rho_t v. The
       * stick/slip test and the slip branch are the plain law's.
       */
      Tensor<2, dim - 1> held;

      /**
       * Anti-cycling (theory.md F8, "status freeze"): keep the contact
       * branch whatever the sign of lambda_aug. Set by the assembly for a
       * point whose status cycled; false for the plain law.
       */
      bool freeze_contact = false;

      /**
       * Anti-cycling: if nonzero, a slip direction (unit tangent vector)
       * that replaces h / |h| while the point is in contact with friction
       * on. The slip branch is then smooth in the unknowns (K_B = 0).
       * Zero for the plain law.
       */
      Tensor<1, dim> frozen_slip_direction;

      /**
       * Anti-cycling: keep the stick branch (P_B(h) = h even if |h| > 1)
       * while the point is in contact with friction on. False for the
       * plain law.
       */
      bool freeze_stick = false;

      /**
       * Active-set search ("release extrapolation"): take the free branch
       * whatever lambda_aug says, for one linear solve. Set by the assembly
       * for a point that ContactProblem::extrapolate_releases() chose;
       * false for the plain law.
       */
      bool release = false;
    };


    /**
     * Residual densities at one contact point and their exact derivatives
     * (doc/theory.md sections 4 and 5) with respect to the point variables
     *   d = u^e(xi^e) - u^m(xi^m)   (relative displacement, dg/dd = n,
     *                                dv/dd = P),
     *   lambda, Lambda.
     *
     * The assembly multiplies by the weight w and shape functions:
     *   R^e_i += w N^e_i force ;  R^m_j -= w N^m_j force ;
     *   R^c_l += w psi_l r_c   ;  R^f_l += w psi_l r_f   ;
     * and, by the chain rule (the sign of a master shape function is minus
     * the slave one in both rows and columns, because d = u^e - u^m):
     *   K_ee = +w N^e_i N^e_j dforce_dd ;   K_em = -w N^e_i N^m_j dforce_dd ;
     *   K_me = -w N^m_i N^e_j dforce_dd ;   K_mm = +w N^m_i N^m_j dforce_dd ;
     *   K_ec = +w N^e_i psi_l dforce_dlambda ;  K_mc = -w N^m_i ... ;
     *   K_ef = +w N^e_i psi_l dforce_dLambda[k] (column k) ; K_mf = -... ;
     *   K_ce = +w psi_l N^e_j drc_dd ; K_cm = -w psi_l N^m_j drc_dd ;
     *   K_cc = +w psi_l psi_m drc_dlambda ;  K_cf = 0 ;
     *   K_fe = +w psi_l N^e_j drf_dd[k] (row k) ; K_fm = -... ;
     *   K_fc = 0 (the rows' weight is held: PointState::row_lambda) ;
     *   K_ff = +w psi_l psi_m drf_dLambda.
     *
     * Units (lambda in [Pa], d in [m]): force [Pa], r_c [m], r_f [Pa m] if
     * the point has an active friction law, [-] otherwise (Lambda itself).
     * The assembly scales the lambda rows by rho_n [Pa/m] and the Lambda
     * rows by rho_t [1/m], so that active rows are forces like R_u.
     * When mu == 0 all friction entries are zero and must not be assembled.
     */
    template <int dim>
    struct PointResponse
    {
      PointStatus status;

      /**
       * chi_c of section 3.1.
       */
      bool in_contact;

      /**
       * true iff the friction rows carry the stick/slip law (mu > 0,
       * in contact, lambda_f != 0); false means they carry r_f = Lambda
       * (free point or zero threshold, section 3.3) or nothing (mu == 0).
       */
      bool friction_active;

      /**
       * Friction threshold lambda_f [Pa] actually used (section 3.3); 0 if
       * mu == 0.
       */
      double lambda_f;

      /**
       * Force density on the slave side, (L_c^e + L_f^e) / (w N^e_i) of
       * section 4 [Pa].
       */
      Tensor<1, dim> force;

      /**
       * Slip direction h / |h| of a slipping point (section 3.2), zero
       * otherwise; lets the caller detect slip reversals between iterates.
       */
      Tensor<1, dim> slip_direction;

      /**
       * Signorini row density [m] (L_c^c / (w psi_l)).
       */
      double r_c;

      /**
       * Coulomb row density, tangent coordinates (L_f^f / (w psi_l)).
       */
      Tensor<1, dim - 1> r_f;

      /**
       * d force / d d [Pa/m].
       */
      Tensor<2, dim> dforce_dd;

      /**
       * d force / d lambda [-].
       */
      Tensor<1, dim> dforce_dlambda;

      /**
       * dforce_dLambda[k] = d force / d Lambda_k [Pa]: column k of the
       * dim x (dim-1) block.
       */
      std::array<Tensor<1, dim>, dim - 1> dforce_dLambda;

      /**
       * d r_c / d d [-]. (d r_c / d Lambda is identically zero.)
       */
      Tensor<1, dim> drc_dd;

      /**
       * d r_c / d lambda [m/Pa].
       */
      double drc_dlambda;

      /**
       * drf_dd[k] = d (r_f)_k / d d: row k of the (dim-1) x dim block.
       */
      std::array<Tensor<1, dim>, dim - 1> drf_dd;

      /**
       * drf_dLambda[k][l] = d (r_f)_k / d Lambda_l.
       */
      Tensor<2, dim - 1> drf_dLambda;
    };


    /**
     * Orthonormal tangent basis for the unit normal @p n (doc/theory.md
     * section 2). 2D: tau_1 = (n_y, -n_x). 3D: tau_1 is the normalised
     * cross product of n with the coordinate axis least aligned with n,
     * tau_2 = n x tau_1, so that (tau_1, tau_2, n) is right-handed (as
     * (tau_1, n) is in 2D). The 3D choice is piecewise smooth in n: if n
     * changes between geometric iterations so that the least aligned axis
     * changes, T rotates, and Lambda must be re-expressed in the new basis.
     */
    template <int dim>
    std::array<Tensor<1, dim>, dim - 1>
    tangent_basis(const Tensor<1, dim> &n);

    /**
     * The coordinate axis tangent_basis() crosses n with (3D: the axis least
     * aligned with n; 0 in 2D).
     */
    template <int dim>
    unsigned int
    tangent_axis(const Tensor<1, dim> &n);

    /**
     * tangent_basis() with the 3D crossing axis given (kept fixed while n
     * moves within a Newton solve, so that T is smooth in n).
     */
    template <int dim>
    std::array<Tensor<1, dim>, dim - 1>
    tangent_basis(const Tensor<1, dim> &n, const unsigned int axis);

    /**
     * The friction condition of a slave node whose displacement is held by
     * Dirichlet conditions along the tangential directions @p held (not
     * necessarily unit, none along the unit normal @p n): the slip along
     * them is zero, so is the friction traction (a symmetry plane), and
     * Lambda keeps only the component the conditions leave free.
     * Returns the unit a, in the frame tangent_basis(n), with
     * a . Lambda = 0 as the node's condition (its largest component
     * positive); zero if @p held is empty; none if the held directions span
     * the tangent plane (2D: any), and the node carries no friction.
     */
    template <int dim>
    std::optional<Tensor<1, dim - 1>>
    held_tangent(const Tensor<1, dim>              &n,
                 const std::vector<Tensor<1, dim>> &held);


    /**
     * Evaluate the contact law at one point: statuses of sections 3.1-3.3,
     * residual densities of section 4 and their exact derivatives of section
     * 5 (with n and T frozen). Pure function: no deal.II assembly.
     */
    template <int dim>
    PointResponse<dim>
    evaluate_contact_law(const PointState<dim> &state,
                         const LawParameters   &parameters);



    /**
     * Normal status decided per multiplier node (pairs with a meshed master on
     * an integration-point rule, `Contact/Statuses = node`): node l is in
     * contact iff lambda_l - rho_n G_l / D_l < 0, with the weighted gap
     * G_l = sum_k w_k psi_l g_k over the paired points of the node's faces
     * and D_l = sum_k w_k psi_l over all of them (psi: the multiplier
     * basis, dual where ContactProblem uses it). Active nodes carry the
     * row G_l = 0, free ones D_l lambda_l = 0, so the converged solution
     * does not depend on rho_n (theory.md F8), as with the nodal rule,
     * of which this is the weighted (mortar) form.
     */
    /**
     * |h| <= 1 + stick_tie is stick (section 3.2): at the first iterate of
     * a step after a slipping one |h| = 1 up to round-off, and the decision
     * must not depend on it (nor on the units). Used by the point law and by
     * the friction status per node.
     */
    constexpr double stick_tie = 1e-12;

    inline bool
    node_in_contact(const double lambda_l,
                    const double weighted_gap,
                    const double weight,
                    const double rho_n)
    {
      return weight > 0 && lambda_l - rho_n * weighted_gap / weight < 0;
    }

    /**
     * The Signorini row density that one point of a node-status pair gives
     * to the row of node l of its face, in the units of PointResponse::r_c
     * (the assembly scales lambda rows by rho_n): an active node
     * r_c = -g (d/dd = -n), a free node r_c = -lambda_l / rho_n with the
     * node's own multiplier (lumped: d/dlambda_l = -1 / rho_n). The point's
     * displacement rows carry the multiplier force -lambda n at every
     * status (lambda is 0 at free nodes).
     */
    template <int dim>
    struct NodeStatusRow
    {
      double         r_c;
      Tensor<1, dim> drc_dd;
      double         drc_dlambda_own;
    };

    template <int dim>
    inline NodeStatusRow<dim>
    node_status_row(const bool            active,
                    const double          gap,
                    const double          lambda_l,
                    const Tensor<1, dim> &n,
                    const double          rho_n)
    {
      if (active)
        return {-gap, -n, 0.};
      return {-lambda_l / rho_n, Tensor<1, dim>(), -1. / rho_n};
    }

  } // namespace Contact
} // namespace Signorini

#endif
