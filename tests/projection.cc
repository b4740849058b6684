// Test of Signorini::Contact::project_onto_face and the rigid obstacles
// (doc/theory.md section 2). Writes "output" via deallog; measured errors go
// to std::cout only (they are round-off and not reproducible bit for bit).

#include <deal.II/base/logstream.h>

#include <deal.II/fe/fe_q.h>

#include <deal.II/base/function_signed_distance.h>
#include <deal.II/physics/transformations.h>

#include <signorini/contact/obstacles/cylinder.h>
#include <signorini/contact/obstacles/level_set.h>
#include <signorini/contact/obstacles/plane.h>
#include <signorini/contact/obstacles/sphere.h>
#include <signorini/contact/projection.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>

using namespace dealii;
using namespace Signorini::Contact;

namespace
{
  std::string
  fmt(const double v, const unsigned int digits = 8)
  {
    const double       eps = 0.5 * std::pow(10., -double(digits));
    std::ostringstream s;
    s << std::fixed << std::setprecision(digits)
      << (std::abs(v) < eps ? 0. : v);
    return s.str();
  }

  template <int d, typename T>
  std::string
  fmt(const T &t, const unsigned int digits = 8)
  {
    std::string s = "(";
    for (unsigned int i = 0; i < d; ++i)
      s += fmt(t[i], digits) + (i + 1 < d ? ", " : ")");
    return s;
  }


  void
  verdict(const std::string &what, const double error, const double tol)
  {
    std::cout << std::setw(58) << std::left << what << " error "
              << std::scientific << std::setprecision(2) << error << std::endl;
    std::ostringstream t;
    t << std::scientific << std::setprecision(0) << tol;
    deallog << what << " recovered to " << t.str() << ": "
            << (error <= tol ? "yes" : "no") << std::endl;
    AssertThrow(error <= tol, ExcMessage(what + " not recovered"));
  }

  void
  expect(const std::string &what, const bool ok)
  {
    deallog << what << ": " << (ok ? "yes" : "no") << std::endl;
    AssertThrow(ok, ExcMessage(what + " failed"));
  }

  template <int dim>
  double
  diameter(const std::vector<Point<dim>> &X)
  {
    double h = 0.;
    for (const auto &a : X)
      for (const auto &b : X)
        h = std::max(h, a.distance(b));
    return h;
  }

  /**
   * p = x* + g n*; project and compare with (xi*, x*, n*, g). Relative
   * tolerance 1e-10 with respect to the face diameter.
   */
  template <int dim>
  void
  check_recovery(const std::string             &name,
                 const std::vector<Point<dim>> &X,
                 const Point<dim>              &inside,
                 const Point<dim - 1>          &xi_star,
                 const Point<dim>              &x_star,
                 const Tensor<1, dim>          &n_star,
                 const double                   g)
  {
    const double     h = diameter(X);
    const Point<dim> p = x_star + g * n_star;
    const auto       r = project_onto_face(p, X, inside);
    deallog << name << ": g = " << fmt(g, 4) << ", xi = " << fmt<dim - 1>(r.xi)
            << ", gap = " << fmt(r.gap) << std::endl;
    expect(name + " converged and inside", r.converged && r.inside);
    verdict(name + " xi", (r.xi - xi_star).norm(), 1e-10);
    verdict(name + " x_m", (r.x_m - x_star).norm() / h, 1e-10);
    verdict(name + " normal", (r.normal - n_star).norm(), 1e-10);
    verdict(name + " gap", std::abs(r.gap - g) / h, 1e-10);
    std::cout << "    (" << r.n_iterations << " Newton iterations)\n";
  }

  // Face map of the discrete FE_Q face, evaluated independently here.
  template <int dim>
  void
  discrete_face(const std::vector<Point<dim>> &X,
                const Point<dim - 1>          &xi,
                const Point<dim>              &inside,
                Point<dim>                    &x,
                Tensor<1, dim>                &n)
  {
    const FE_Q<dim - 1> fe(X.size() == (dim == 2 ? 3u : 9u) ? 2 : 1);
    x = Point<dim>();
    Tensor<1, dim> a[dim - 1];
    for (unsigned int k = 0; k < X.size(); ++k)
      {
        x += fe.shape_value(k, xi) * X[k];
        for (unsigned int d = 0; d < dim - 1; ++d)
          a[d] += fe.shape_grad(k, xi)[d] * X[k];
      }
    if constexpr (dim == 2)
      n = Tensor<1, 2>({a[0][1], -a[0][0]});
    else
      n = cross_product_3d(a[0], a[1]);
    n /= n.norm();
    if (n * (inside - x) < 0)
      n = -n;
  }

  // ---------------------------------------------------------------- cases

  void
  test_ordering()
  {
    deallog << "--- FE_Q<dim-1> face support point ordering" << std::endl;
    for (unsigned int deg = 1; deg <= 2; ++deg)
      {
        const FE_Q<1> fe1(deg);
        const FE_Q<2> fe2(deg);
        std::string   s1, s2;
        for (const auto &q : fe1.get_unit_support_points())
          s1 += " " + fmt<1>(q, 1);
        for (const auto &q : fe2.get_unit_support_points())
          s2 += " " + fmt<2>(q, 1);
        deallog << "FE_Q<1>(" << deg << "):" << s1 << std::endl;
        deallog << "FE_Q<2>(" << deg << "):" << s2 << std::endl;
        double err = 0.;
        for (unsigned int i = 0; i < fe2.n_dofs_per_cell(); ++i)
          for (unsigned int j = 0; j < fe2.n_dofs_per_cell(); ++j)
            err =
              std::max(err,
                       std::abs(
                         fe2.shape_value(i, fe2.get_unit_support_points()[j]) -
                         (i == j)));
        for (unsigned int i = 0; i < fe1.n_dofs_per_cell(); ++i)
          for (unsigned int j = 0; j < fe1.n_dofs_per_cell(); ++j)
            err =
              std::max(err,
                       std::abs(
                         fe1.shape_value(i, fe1.get_unit_support_points()[j]) -
                         (i == j)));
        verdict("Q" + std::to_string(deg) + " N_i(x_j) = delta_ij", err, 1e-14);
      }
  }

  void
  test_q1_line()
  {
    deallog << "--- Q1 line (2D)" << std::endl;
    const std::vector<Point<2>> X = {Point<2>(1., 2.), Point<2>(4., 6.)};
    const Tensor<1, 2>          n({-0.8, 0.6}); // into the master body
    const Point<2>              inside = Point<2>(2.5, 4.) + 2. * n;
    const Point<1>              xi(0.3);
    const Point<2>              x = X[0] + 0.3 * (X[1] - X[0]);
    check_recovery<2>("Q1 line, penetrating", X, inside, xi, x, n, 0.7);
    check_recovery<2>("Q1 line, separated", X, inside, xi, x, n, -1.3);
  }

  void
  test_q1_quad()
  {
    deallog << "--- Q1 quad, planar (3D)" << std::endl;
    {
      const Point<3>              O(0.5, -1., 2.);
      const Tensor<1, 3>          A({2., 0., 0.5}), B({0.3, 1.5, 0.2});
      const std::vector<Point<3>> X = {O, O + A, O + B, O + A + B};
      Tensor<1, 3>                n = cross_product_3d(A, B);
      n /= n.norm();
      const Point<3> inside = O + 0.5 * (A + B) - 0.7 * n; // n points away
      n                     = -n;
      const Point<2> xi(0.2, 0.65);
      const Point<3> x = O + 0.2 * A + 0.65 * B;
      check_recovery<3>(
        "Q1 planar quad, penetrating", X, inside, xi, x, n, 0.4);
      check_recovery<3>("Q1 planar quad, separated", X, inside, xi, x, n, -2.);
    }
    deallog << "--- Q1 quad, non-planar bilinear (3D)" << std::endl;
    {
      const std::vector<Point<3>> X = {Point<3>(0., 0., 0.),
                                       Point<3>(1., 0., 0.1),
                                       Point<3>(0., 1., -0.1),
                                       Point<3>(1.2, 1.1, 0.4)};
      const double                u = 0.62, v = 0.27;
      const Point<3> x = (1 - u) * (1 - v) * X[0] + u * (1 - v) * X[1] +
                         (1 - u) * v * X[2] + u * v * X[3];
      const Tensor<1, 3> au = (1 - v) * (X[1] - X[0]) + v * (X[3] - X[2]);
      const Tensor<1, 3> av = (1 - u) * (X[2] - X[0]) + u * (X[3] - X[1]);
      Tensor<1, 3>       n  = cross_product_3d(au, av);
      n /= n.norm();
      if (n[2] > 0) // master body below (z < 0)
        n = -n;
      const Point<3> inside(0.5, 0.5, -1.);
      check_recovery<3>(
        "Q1 bilinear quad, penetrating", X, inside, Point<2>(u, v), x, n, 0.15);
      check_recovery<3>(
        "Q1 bilinear quad, separated", X, inside, Point<2>(u, v), x, n, -0.3);
    }
  }

  /**
   * Seven projections recorded from the hemispheres scene (tests/
   * contact_hemispheres_3d.prm, one rank, metres): points 1 to 3 mm from
   * 4 mm faces, six of them inside the face and one just outside. The line
   * search on f halved the last Newton steps at round-off, and all seven
   * ended unconverged after 30 iterations, so that the pairing dropped the
   * face (on 2 ranks it then paired a contact point with a face 2 mm away).
   * Each must converge to a point where x(xi) - p is orthogonal to the
   * face (|r . a_k| <= 1e-10 |r| |a_k|).
   */
  void
  test_recorded_cases()
  {
    deallog << "--- Recorded round-off cases (3D)" << std::endl;
    struct Case
    {
      double p[3], inside[3], X[4][3];
    };
    const std::vector<Case> cases = {
      {{-0.0053125141232540337, -0.0089371531441456396, 0.0011310542261792362},
       {-0.0044770831115283089, -0.006568923415029077, -0.0030449196841275507},
       {{-0.0053179017037081446, -0.009247680416266623, -0.0011512504930955641},
        {-0.0053144266908982836,
         -0.0054640363016447988,
         -0.00058440351223739556},
        {-0.0016161508053191161,
         -0.006474931665643671,
         -0.00044736821822970868},
        {-0.0028453121061348991,
         -0.0048697392678961338,
         -0.00031911999087181481}}},
      {{-0.010195188597246481, -0.0076804450320556768, 0.00172286284604132},
       {-0.0083769971275751472, -0.0076999643845487263, -0.0036950533119898357},
       {{-0.0053179017037081446, -0.009247680416266623, -0.0011512504930955641},
        {-0.010448761973999601, -0.0082893227300764889, -0.0018117182098454851},
        {-0.007512323522502814, -0.0068496299527523218, -0.001044432749649313},
        {-0.01019733758407641,
         -0.0070013420187472414,
         -0.0015542002219706701}}},
      {{-0.01149888901612311, 0.0055335093883042766, 0.0012385150516672316},
       {-0.011363003199974865, 0.0034847093248849817, -0.0031507700728437902},
       {{-0.011756666097690978, 0.0054179606066703913, -0.0012792711188018939},
        {-0.013723667055880044, -3.4782434961657925e-05, -0.001488233250737451},
        {-0.010411623699840651, 0.0050440436789185193, -0.00094256793515480727},
        {-0.010742185352255787,
         0.0021354256519617552,
         -0.00080468944967951707}}},
      {{-0.020382582998135265, -0.019601347542549656, 0.008353009174613079},
       {-0.014019138539691141, -0.012650128170365125, -0.0058555340351263566},
       {{-0.012804740889083654, -0.01542776589978684, -0.0037313809875487805},
        {-0.018253244824978428, -0.015836490900133927, -0.0057500760140761081},
        {-0.013739028190813355, -0.01272823295504383, -0.0031801120073246501},
        {-0.016934083942779805,
         -0.011589459911015039,
         -0.0039386949116302162}}},
      {{0.0046132297534210243, 0.0086307570016603882, 0.00057941343150239857},
       {0.0028661082353589702, 0.0079976024085864246, -0.0028480623295054916},
       {{0.0019008387409330042, 0.0091558125947728379, -0.00048919423591047288},
        {0.0017839083188870911, 0.011931403213074641, -0.0010638820803227631},
        {0.0039064741451730334, 0.0078181740811347003, -0.00039757598062024608},
        {0.0048545606428237256,
         0.008548414654409876,
         -0.00058794299015134052}}},
      {{0.0050672137037718655, -0.014766748496273175, 0.0020742711383814564},
       {0.0056542159081220166, -0.012711539574291419, -0.0035906476980556738},
       {{0.0057357401017600522, -0.015943932133391341, -0.0025072175573063776},
        {0.0080010850927026995, -0.015362346369444163, -0.0026404119179978622},
        {0.002840076006200135, -0.013726526475929956, -0.0015701532222664812},
        {0.0044615534969892102,
         -0.010380968163783545,
         -0.00088000000760991078}}},
      {{0.0064974124360577343, 0.015405495618168846, 0.0024790040394279669},
       {0.0050596635754338237, 0.014688079393949217, -0.0054400391565608535},
       {{0.0038710599166336436, 0.017016758882470638, -0.0026902892919047272},
        {0.0061103172741384937, 0.015785171906885585, -0.0025022262073024965},
        {0.0017839292057290647, 0.011931895326522031, -0.0010642186634724662},
        {0.0061716423464364565, 0.012619855603987849, -0.0015804781784929717}}},
    };
    const auto point = [](const double(&a)[3]) {
      return Point<3>(a[0], a[1], a[2]);
    };
    double       worst       = 0;
    unsigned int n_converged = 0;
    for (const auto &c : cases)
      {
        std::vector<Point<3>> X;
        for (const auto &x : c.X)
          X.push_back(point(x));
        const Point<3> p = point(c.p);
        const auto     r = project_onto_face(p, X, point(c.inside));
        n_converged += r.converged;
        const auto         geometry = face_geometry<3>(X, r.xi);
        const Tensor<1, 3> d        = geometry.x - p;
        for (const auto &a : geometry.tangents)
          worst = std::max(worst, std::abs(d * a) / (d.norm() * a.norm()));
        std::cout << "    (" << r.n_iterations << " Newton iterations)\n";
      }
    deallog << n_converged << " of " << cases.size() << " converged"
            << std::endl;
    expect("every recorded case converged", n_converged == cases.size());
    verdict("recorded cases: orthogonality", worst, 1e-10);
  }


  void
  test_q2_arc()
  {
    deallog << "--- Q2 line on a circle arc (2D)" << std::endl;
    const Point<2> C(0.5, -0.2);
    const double   R   = 2.;
    const auto     arc = [&](const double t) {
      return C + R * Point<2>(std::cos(t), std::sin(t));
    };
    // FE_Q<1>(2) order: end 0, end 1, midpoint
    const std::vector<Point<2>> X = {arc(0.3), arc(0.9), arc(0.6)};
    const Point<1>              xi(0.37);
    Point<2>                    x;
    Tensor<1, 2>                n;
    discrete_face<2>(X, xi, C, x, n);
    deallog << "discrete arc radius at xi*: " << fmt(x.distance(C), 6)
            << " (circle: " << fmt(R, 6) << ")" << std::endl;
    check_recovery<2>("Q2 arc, penetrating", X, C, xi, x, n, 0.05);
    check_recovery<2>("Q2 arc, separated", X, C, xi, x, n, -0.3);
  }

  void
  test_q2_sphere()
  {
    deallog << "--- Q2 quad on a sphere patch (3D)" << std::endl;
    const Point<3> C(0.1, 0.2, -0.3);
    const double   R      = 1.5;
    const auto     sphere = [&](const Point<2> &s) {
      const double th = 0.2 + 0.5 * s[0], ph = 0.9 + 0.4 * s[1];
      return C + R * Point<3>(std::sin(ph) * std::cos(th),
                              std::sin(ph) * std::sin(th),
                              std::cos(ph));
    };
    const FE_Q<2>         fe(2); // must outlive the loop below
    std::vector<Point<3>> X;
    for (const auto &s : fe.get_unit_support_points())
      X.push_back(sphere(s));
    const Point<2> xi(0.31, 0.72);
    Point<3>       x;
    Tensor<1, 3>   n;
    discrete_face<3>(X, xi, C, x, n);
    deallog << "discrete patch radius at xi*: " << fmt(x.distance(C), 6)
            << " (sphere: " << fmt(R, 6) << ")" << std::endl;
    check_recovery<3>("Q2 sphere patch, penetrating", X, C, xi, x, n, 0.05);
    check_recovery<3>("Q2 sphere patch, separated", X, C, xi, x, n, -0.4);
  }

  void
  test_outside()
  {
    deallog << "--- projections outside the face" << std::endl;
    const std::vector<Point<2>> L = {Point<2>(0., 0.), Point<2>(1., 0.)};
    const Point<2>              inside(0.5, -1.);
    {
      const auto r = project_onto_face(Point<2>(1.2, 0.1), L, inside);
      deallog << "line, p = (1.2, 0.1): xi = " << fmt<1>(r.xi)
              << ", inside = " << (r.inside ? "true" : "false")
              << ", violation = " << fmt(r.violation)
              << ", gap = " << fmt(r.gap) << std::endl;
      expect("converged, inside == false", r.converged && !r.inside);
      verdict("violation 0.2", std::abs(r.violation - 0.2), 1e-10);
      verdict("gap -0.1 (separated)", std::abs(r.gap + 0.1), 1e-10);
    }
    {
      const auto r =
        project_onto_face(Point<2>(1. + 1e-6, -0.05), L, inside, 1e-8);
      deallog << "line, 1e-6 beyond the end, tol_xi = 1e-8: inside = "
              << (r.inside ? "true" : "false") << std::endl;
      expect("slightly outside -> inside == false", !r.inside);
      verdict("violation 1e-6", std::abs(r.violation - 1e-6), 1e-12);
      const auto q =
        project_onto_face(Point<2>(1. + 1e-10, -0.05), L, inside, 1e-8);
      deallog << "line, 1e-10 beyond the end, tol_xi = 1e-8: inside = "
              << (q.inside ? "true" : "false") << std::endl;
      expect("within tol_xi -> inside == true", q.inside);
    }
    {
      // convex corner at (1,0): the point projects outside both faces; the
      // smaller violation selects the face.
      const std::vector<Point<2>> F2 = {Point<2>(1., 0.), Point<2>(2., -1.)};
      const Point<2>              p(1.05, 0.2);
      const auto                  r1 = project_onto_face(p, L, inside);
      const auto                  r2 = project_onto_face(p, F2, inside);
      deallog << "corner: face 1 violation " << fmt(r1.violation)
              << ", face 2 violation " << fmt(r2.violation) << std::endl;
      expect("both outside, face 1 picked",
             !r1.inside && !r2.inside && r1.violation < r2.violation);
      verdict("face 1 violation 0.05", std::abs(r1.violation - 0.05), 1e-10);
      verdict("face 2 violation 0.075", std::abs(r2.violation - 0.075), 1e-10);
    }
    {
      const Tensor<1, 3>          A({1., 0., 0.}), B({0., 2., 0.});
      const std::vector<Point<3>> Q = {Point<3>(),
                                       Point<3>() + A,
                                       Point<3>() + B,
                                       Point<3>() + A + B};
      const auto r = project_onto_face(Point<3>(-0.05, 2.04, 0.3),
                                       Q,
                                       Point<3>(0.5, 1., -1.));
      deallog << "quad, beyond a corner: xi = " << fmt<2>(r.xi)
              << ", violation = " << fmt(r.violation) << std::endl;
      expect("quad corner inside == false", r.converged && !r.inside);
      verdict("quad corner violation 0.05",
              std::abs(r.violation - 0.05),
              1e-10);
      verdict("quad corner gap -0.3", std::abs(r.gap + 0.3), 1e-10);
    }
  }

  template <int dim>
  void
  check_rigid(const std::string                           &name,
              const Signorini::Obstacles::Projection<dim> &r,
              const Point<dim>                            &x_m,
              const Tensor<1, dim>                        &n,
              const double                                 g)
  {
    deallog << name << ": x_m = " << fmt<dim>(r.x_m)
            << ", n = " << fmt<dim>(r.normal) << ", g = " << fmt(r.gap)
            << std::endl;
    verdict(name + " x_m", (r.x_m - x_m).norm(), 1e-12);
    verdict(name + " normal", (r.normal - n).norm(), 1e-12);
    verdict(name + " gap", std::abs(r.gap - g), 1e-12);
    expect(name + " normal unit", std::abs(r.normal.norm() - 1.) < 1e-14);
  }

  void
  test_rigid()
  {
    deallog << "--- rigid obstacles" << std::endl;
    {
      // obstacle y < 1 (outward normal +y); contact normal -y (into it)
      Signorini::Obstacles::Plane<2> plane(Point<2>(0., 1.),
                                           Tensor<1, 2>({0., 3.}));
      check_rigid<2>("plane 2D, penetrating",
                     plane.project(Point<2>(0.3, 0.9)),
                     Point<2>(0.3, 1.),
                     Tensor<1, 2>({0., -1.}),
                     0.1);
      plane.set_translation(Tensor<1, 2>({7., 0.5}));
      check_rigid<2>("plane 2D, translated (0,0.5)",
                     plane.project(Point<2>(0.3, 0.9)),
                     Point<2>(0.3, 1.5),
                     Tensor<1, 2>({0., -1.}),
                     0.6);
      check_rigid<2>("plane 2D, translated, separated",
                     plane.project(Point<2>(-2., 2.)),
                     Point<2>(-2., 1.5),
                     Tensor<1, 2>({0., -1.}),
                     -0.5);
    }
    {
      const Tensor<1, 3>             nu({1., 2., 2.}); // |nu| = 3
      Signorini::Obstacles::Plane<3> plane(Point<3>(1., 0., 0.), nu);
      // p = x0 + 0.5 t - 0.3 nu/3 with t orthogonal to nu
      const Tensor<1, 3> t({2., -1., 0.});
      const Point<3>     p = Point<3>(1., 0., 0.) + 0.5 * t - 0.1 * nu;
      check_rigid<3>("plane 3D, penetrating",
                     plane.project(p),
                     Point<3>(1., 0., 0.) + 0.5 * t,
                     -nu / 3.,
                     0.3);
    }
    {
      Signorini::Obstacles::Sphere<2> circle(Point<2>(1., 1.), 2.);
      check_rigid<2>("circle, penetrating",
                     circle.project(Point<2>(1. + 0.6 * 1.5, 1. + 0.8 * 1.5)),
                     Point<2>(1. + 0.6 * 2., 1. + 0.8 * 2.),
                     Tensor<1, 2>({-0.6, -0.8}),
                     0.5);
      circle.set_translation(Tensor<1, 2>({0., -1.}));
      check_rigid<2>("circle, translated (0,-1), separated",
                     circle.project(Point<2>(1., -3.5)),
                     Point<2>(1., -2.),
                     Tensor<1, 2>({0., 1.}),
                     -1.5);
    }
    {
      const Point<3>                  c(1., 2., 3.);
      Signorini::Obstacles::Sphere<3> sphere(c, 2.);
      check_rigid<3>("sphere, penetrating",
                     sphere.project(c + Tensor<1, 3>({0., 0., 1.5})),
                     c + Tensor<1, 3>({0., 0., 2.}),
                     Tensor<1, 3>({0., 0., -1.}),
                     0.5);
      check_rigid<3>("sphere, separated",
                     sphere.project(c + Tensor<1, 3>({1.8, 0., 2.4})),
                     c + Tensor<1, 3>({1.2, 0., 1.6}),
                     Tensor<1, 3>({-0.6, 0., -0.8}),
                     -1.);
    }
    {
      Signorini::Obstacles::Cylinder<3> cyl(Point<3>(0., 0., 1.),
                                            Tensor<1, 3>({0., 0., 2.}),
                                            1.);
      check_rigid<3>("cylinder, separated",
                     cyl.project(Point<3>(1.2, 1.6, 7.)),
                     Point<3>(0.6, 0.8, 7.),
                     Tensor<1, 3>({-0.6, -0.8, 0.}),
                     -1.);
      cyl.set_translation(Tensor<1, 3>({1., 0., 0.}));
      check_rigid<3>("cylinder, translated (1,0,0), penetrating",
                     cyl.project(Point<3>(1., -0.25, -4.)),
                     Point<3>(1., -1., -4.),
                     Tensor<1, 3>({0., 1., 0.}),
                     0.75);
      // oblique axis e = (1,1,0)/sqrt(2), p = a + 3 e + 0.5 z
      Signorini::Obstacles::Cylinder<3> ob(Point<3>(),
                                           Tensor<1, 3>({1., 1., 0.}),
                                           0.8);
      const Tensor<1, 3> e = Tensor<1, 3>({1., 1., 0.}) / std::sqrt(2.);
      check_rigid<3>("cylinder, oblique axis, penetrating",
                     ob.project(Point<3>() + 3. * e +
                                Tensor<1, 3>({0., 0., 0.5})),
                     Point<3>() + 3. * e + Tensor<1, 3>({0., 0., 0.8}),
                     Tensor<1, 3>({0., 0., -1.}),
                     0.3);
    }
    {
      Signorini::Obstacles::Cylinder<2> disk(Point<2>(0., 0.),
                                             Tensor<1, 2>(),
                                             1.);
      check_rigid<2>("cylinder 2D (disk), penetrating",
                     disk.project(Point<2>(0., -0.4)),
                     Point<2>(0., -1.),
                     Tensor<1, 2>({0., 1.}),
                     0.6);
    }
  }

  /**
   * dn/dp and dx^m/dp of an obstacle against central differences of its
   * projection (step 1e-6), relative to the largest entry, to @p tol; and
   * the gap consistent with them: g = (p - x^m) . n.
   */
  template <int dim>
  void
  check_rigid_derivatives(const std::string                          &name,
                          const Signorini::Obstacles::Interface<dim> &obstacle,
                          const Point<dim>                           &p,
                          const double                                tol)
  {
    const auto     r = obstacle.project(p);
    const double   h = 1e-6;
    Tensor<2, dim> dn, dx;
    for (unsigned int j = 0; j < dim; ++j)
      {
        Point<dim> plus = p, minus = p;
        plus[j] += h;
        minus[j] -= h;
        const auto rp = obstacle.project(plus), rm = obstacle.project(minus);
        for (unsigned int i = 0; i < dim; ++i)
          {
            dn[i][j] = (rp.normal[i] - rm.normal[i]) / (2 * h);
            dx[i][j] = (rp.x_m[i] - rm.x_m[i]) / (2 * h);
          }
      }
    const double scale = std::max(1., dx.norm());
    verdict(name + " dn/dp", (dn - r.dnormal).norm() / scale, tol);
    verdict(name + " dx^m/dp", (dx - r.dclosest).norm() / scale, tol);
    verdict(name + " g = (p - x^m) . n",
            std::abs((p - r.x_m) * r.normal - r.gap),
            1e-12);
  }

  /**
   * The obstacles' derivatives at generic points, and the level set: the
   * signed distance of a sphere as an expression (derivatives by
   * differences) and as Functions::SignedDistance::Sphere (exact) gives
   * the sphere's projection.
   */
  void
  test_rigid_derivatives()
  {
    deallog << "--- rigid obstacle derivatives" << std::endl;
    check_rigid_derivatives<2>(
      "plane 2D",
      Signorini::Obstacles::Plane<2>(Point<2>(0., 1.), Tensor<1, 2>({1., 3.})),
      Point<2>(0.3, 0.9),
      1e-8);
    check_rigid_derivatives<3>(
      "sphere 3D",
      Signorini::Obstacles::Sphere<3>(Point<3>(1., 2., 3.), 2.),
      Point<3>(1.5, 2.7, 4.1),
      1e-8);
    check_rigid_derivatives<3>("cylinder 3D, oblique axis",
                               Signorini::Obstacles::Cylinder<3>(
                                 Point<3>(), Tensor<1, 3>({1., 1., 0.}), 0.8),
                               Point<3>(0.4, 1.1, 0.5),
                               1e-8);
    check_rigid_derivatives<2>("cylinder 2D (disk)",
                               Signorini::Obstacles::Cylinder<2>(Point<2>(),
                                                                 Tensor<1, 2>(),
                                                                 1.),
                               Point<2>(0.3, -0.7),
                               1e-8);

    // A rigid motion: a quarter turn counterclockwise about (1, 0), then
    // the translation (0, 2). The plane y < 0 (outward normal +y) becomes
    // the half-plane x > 1 shifted up: outward normal -x, contact normal
    // +x; the point (0.5, 2.3) is 0.5 outside it, its closest point
    // (1, 2.3).
    {
      Signorini::Obstacles::Plane<2> plane(Point<2>(), Tensor<1, 2>({0., 1.}));
      Signorini::Obstacles::RigidMotion<2> motion;
      motion.rotation    = Tensor<2, 2>({{0., -1.}, {1., 0.}});
      motion.centre      = Point<2>(1., 0.);
      motion.translation = Tensor<1, 2>({0., 2.});
      plane.set_motion(motion);
      check_rigid<2>("plane, quarter turn about (1, 0), translated (0, 2)",
                     plane.project(Point<2>(0.5, 2.3)),
                     Point<2>(1., 2.3),
                     Tensor<1, 2>({1., 0.}),
                     -0.5);
      Signorini::Obstacles::Sphere<3>      ball(Point<3>(1., 2., 3.), 2.);
      Signorini::Obstacles::RigidMotion<3> turn;
      const Tensor<1, 3> axis = Tensor<1, 3>({1., 2., 2.}) / 3.;
      turn.rotation =
        Physics::Transformations::Rotations::rotation_matrix_3d(axis, 0.7);
      turn.centre      = Point<3>(0., 1., 0.);
      turn.translation = Tensor<1, 3>({0.1, -0.2, 0.3});
      ball.set_motion(turn);
      check_rigid_derivatives<3>("sphere, turned about an oblique axis",
                                 ball,
                                 Point<3>(1.5, 2.7, 4.1),
                                 1e-8);
    }

    const Point<3>                  c(1., 2., 3.);
    Signorini::Obstacles::Sphere<3> sphere(c, 2.);
    ParameterHandler                prm;
    Signorini::Obstacles::LevelSet<3>::declare_parameters(prm);
    prm.parse_input_from_string(
      "subsection Level set\n"
      "  set Function = sqrt((x-a)^2 + (y-b)^2 + (z-c)^2) - R\n"
      "  set Function constants = a: 1, b: 2, c: 3, R: 2\n"
      "end\n");
    Signorini::Obstacles::LevelSet<3> expression;
    expression.parse_parameters(prm);
    expression.set_length_scale(0.1);
    deallog << "expression: " << expression.approximate_derivatives()
            << std::endl;
    Signorini::Obstacles::LevelSet<3> exact;
    exact.set_function(
      std::make_shared<Functions::SignedDistance::Sphere<3>>(c, 2.),
      true,
      true);
    expect("exact level set: derivatives exact",
           exact.approximate_derivatives().empty());
    for (const auto &p : {Point<3>(1.5, 2.7, 4.1), Point<3>(2.9, 1.5, 3.2)})
      {
        const auto s = sphere.project(p);
        for (const auto *level_set : {&expression, &exact})
          {
            const auto        r = level_set->project(p);
            const std::string name =
              std::string("level set (") +
              (level_set == &exact ? "exact" : "expression") + ") = sphere";
            const double tol = level_set == &exact ? 1e-12 : 5e-10;
            verdict(name + ": x_m", (r.x_m - s.x_m).norm(), tol);
            verdict(name + ": normal", (r.normal - s.normal).norm(), tol);
            verdict(name + ": gap", std::abs(r.gap - s.gap), tol);
            verdict(name + ": dn/dp",
                    (r.dnormal - s.dnormal).norm(),
                    level_set == &exact ? 1e-12 : 2e-8);
            verdict(name + ": dx^m/dp",
                    (r.dclosest - s.dclosest).norm(),
                    level_set == &exact ? 1e-12 : 2e-8);
          }
        check_rigid_derivatives<3>("level set (exact)", exact, p, 1e-8);
      }
  }
} // namespace


int
main()
{
  std::ofstream logfile("output");
  deallog.attach(logfile, /*print_job_id=*/false);
  deallog.depth_console(0);

  test_ordering();
  test_q1_line();
  test_q1_quad();
  test_recorded_cases();
  test_q2_arc();
  test_q2_sphere();
  test_outside();
  test_rigid();
  test_rigid_derivatives();

  deallog << "OK" << std::endl;
  std::cout << "all checks passed" << std::endl;
  return 0;
}
