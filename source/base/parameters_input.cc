// Consistency checks across subsections and reading a parameter file or
// text.
#include <deal.II/base/utilities.h>

#include <signorini/base/input_checks.h>
#include <signorini/base/parameters.h>
#include <signorini/base/shared_libraries.h>

#include <signorini/base/parameter_helpers.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <regex>
#include <sstream>

namespace Signorini
{
  using internal::component_index;
  using internal::point_pattern;
  using internal::to_doubles;
  using internal::to_unsigned;

  namespace
  {
    // A Dirichlet condition in the normal/tangential frame or along a
    // direction: alone in 'Components', Dimension expressions (normal,
    // tangential: a vector) or one (direction), a nonzero direction, no
    // 'At point'.
    void
    check_dirichlet_frame(const DirichletParameters &d,
                          const std::string         &where,
                          const unsigned int         dim)
    {
      const std::string name =
        d.frame == DirichletFrame::normal     ? "normal" :
        d.frame == DirichletFrame::tangential ? "tangential" :
                                                "direction";
      if (d.component_names.size() != 1)
        throw InputError(where + ", parameter 'Components': '" + name +
                         "' stands alone (it is not combined with x, y, z, "
                         "normal, tangential or direction). Use one "
                         "condition per kind.");
      const unsigned int expected =
        d.frame == DirichletFrame::direction ? 1 : dim;
      if (d.values.size() != expected)
        throw InputError(
          where + ", parameter 'Values': " + std::to_string(d.values.size()) +
          " expression(s) for Components = " + name + "; give " +
          (expected == 1 ? std::string("one expression (the displacement "
                                       "along 'Direction')") :
                           std::to_string(dim) +
                             " expressions separated by ';' (a vector whose " +
                             name + " part is imposed)") +
          ".");
      if (!d.at_point.empty())
        throw InputError(where + ", parameter 'At point': it takes Cartesian "
                                 "components; use x, y(, z) in 'Components'.");
      if (d.frame == DirichletFrame::direction)
        {
          double norm = 0;
          for (const double v : d.direction)
            norm += v * v;
          if (d.direction.size() != dim || norm == 0)
            throw InputError(where + ", parameter 'Direction': give " +
                             std::to_string(dim) +
                             " numbers, not all zero, for Components = "
                             "direction.");
        }
      else if (!d.direction.empty())
        throw InputError(where + ", parameter 'Direction': it is for "
                                 "Components = direction; remove it.");
    }


    // The boundary conditions against the dimension: components, one
    // expression per component, points.
    void
    check_boundary_conditions(const BoundaryConditionParameters &bc,
                              const unsigned int                 dim)
    {
      const auto &boundary_conditions = bc;
      for (unsigned int k = 0; k < boundary_conditions.dirichlet.size(); ++k)
        {
          const auto       &d = boundary_conditions.dirichlet[k];
          const std::string where =
            "subsection 'Boundary conditions/Dirichlet " +
            std::to_string(k + 1) + "'";
          if (d.frame != DirichletFrame::cartesian)
            {
              check_dirichlet_frame(d, where, dim);
              continue;
            }
          if (!d.direction.empty())
            throw InputError(where + ", parameter 'Direction': it is for "
                                     "Components = direction; remove it.");
          for (const unsigned int c : d.components)
            if (c >= dim)
              throw InputError(where +
                               ", parameter 'Components': component z does not "
                               "exist for Dimension = 2. Use x and/or y.");
          // A component listed twice would take the value of its first
          // expression only, silently.
          for (unsigned int i = 0; i < d.components.size(); ++i)
            if (std::count(d.components.begin(),
                           d.components.begin() + i,
                           d.components[i]))
              throw InputError(where + ", parameter 'Components': component " +
                               std::string(1, "xyz"[d.components[i]]) +
                               " is listed twice. List each component once, "
                               "with one expression per listed component in "
                               "'Values'.");
          if (d.values.size() != d.components.size())
            throw InputError(
              where +
              ", parameter 'Values': " + std::to_string(d.values.size()) +
              " expression(s) for " + std::to_string(d.components.size()) +
              " component(s). Give one expression per listed "
              "component, separated by ';'.");
          if (!d.at_point.empty() && d.at_point.size() != dim)
            throw InputError(where + ", parameter 'At point': give " +
                             std::to_string(dim) + " coordinates.");
        }
      for (unsigned int k = 0; k < boundary_conditions.neumann.size(); ++k)
        {
          const auto        &n = boundary_conditions.neumann[k];
          const unsigned int expected =
            n.type == NeumannType::traction ? dim : 1;
          if (n.values.size() != expected)
            throw InputError(
              "subsection 'Boundary conditions/Neumann " +
              std::to_string(k + 1) +
              "', parameter 'Values': " + std::to_string(n.values.size()) +
              " expression(s) given, " + std::to_string(expected) +
              " expected for this Type and Dimension.");
        }
    }


    // A rigid obstacle's motion: dim translations, a rotation (one angle
    // in 2D, a rotation vector in 3D, or 0) and its centre.
    void
    check_obstacle_motion(const ContactPairParameters &p,
                          const std::string           &where,
                          const unsigned int           dim)
    {
      if (p.obstacle_motion.size() < dim)
        throw InputError(where + ", parameter 'Obstacle motion': give " +
                         std::to_string(dim) +
                         " expressions separated by ';'.");
      const bool no_rotation = p.obstacle_rotation.size() == 1 &&
                               Utilities::trim(p.obstacle_rotation[0]) == "0";
      if (!no_rotation && p.obstacle_rotation.size() != (dim == 2 ? 1u : 3u))
        throw InputError(where + ", parameter 'Obstacle rotation': give " +
                         (dim == 2 ?
                            std::string("the angle [rad] as one expression "
                                        "of t") :
                            std::string("the rotation vector (axis times "
                                        "angle [rad]) as 3 expressions of t "
                                        "separated by ';'")) +
                         ", or 0.");
      if (p.rotation_centre.size() < dim)
        throw InputError(where + ", parameter 'Rotation centre': give " +
                         std::to_string(dim) + " coordinates.");
    }
  } // namespace


  void
  Parameters::check_consistency() const
  {
    const unsigned int dim = dimension;
    check_boundary_conditions(boundary_conditions, dim);
    std::map<unsigned int, unsigned int> seen;
    for (unsigned int k = 0; k < materials.size(); ++k)
      if (!seen.emplace(materials[k].material_id, k).second)
        throw InputError(
          "subsection 'Materials/Material " + std::to_string(k + 1) +
          "', parameter 'Material id': id " +
          std::to_string(materials[k].material_id) +
          " is already used by Material " +
          std::to_string(seen[materials[k].material_id] + 1) + ".");
    for (unsigned int k = 0; k < materials.size(); ++k)
      if (materials[k].body_force.size() < dim)
        throw InputError("subsection 'Materials/Material " +
                         std::to_string(k + 1) +
                         "', parameter 'Body force': give at least "
                         "Dimension expressions separated by ';'.");
    check_contact();
  }


  // The contact settings against each other, the element degree, the
  // linear solver and the dimension.
  void
  Parameters::check_contact() const
  {
    const unsigned int dim = dimension;
    const auto        &c   = contact;
    if (c.rule == IntegrationRule::newton_cotes && c.order != 1 &&
        c.order != 2 && c.order != 4 && c.order != 6)
      throw InputError("subsection 'Contact', parameter 'Integration order': "
                       "the newton-cotes rule exists for orders 1, 2, 4 and 6 "
                       "(trapezoid, Simpson, Milne, Weddle), not " +
                       std::to_string(c.order) + ".");
    // A face of degree k carries k + 1 multiplier nodes per direction: a
    // rule with fewer points per face direction leaves a combination of
    // them untied, and the tangent is singular (MUMPS: a null pivot).
    const bool         gauss  = c.rule == IntegrationRule::gauss;
    const unsigned int points = gauss ? c.order : c.order + 1;
    if (!c.pairs.empty() && fe_degree <= 2 &&
        (gauss || c.rule == IntegrationRule::newton_cotes) &&
        points < fe_degree + 1)
      throw InputError(
        "subsection 'Contact', parameter 'Integration order': the " +
        std::string(gauss ? "gauss" : "newton-cotes") + " rule of order " +
        std::to_string(c.order) + " has " + std::to_string(points) +
        " point(s) per face direction, fewer than the " +
        std::to_string(fe_degree + 1) + " multiplier nodes of a Q" +
        std::to_string(fe_degree) +
        " face: the contact tangent would be singular. Set 'Integration "
        "order' to at least " +
        std::to_string(gauss ? fe_degree + 1 : fe_degree) +
        " (or use the mortar or nodal rule).");
    if (axisymmetric && dimension != 2)
      throw InputError("parameter 'Axisymmetric': an axisymmetric model is a "
                       "2D meridian section; set 'Dimension = 2' or "
                       "'Axisymmetric = false'.");
    if (plane_stress && (dimension != 2 || axisymmetric))
      throw InputError("parameter 'Plane stress': it is a 2D model of a "
                       "thin part; set 'Dimension = 2' and 'Axisymmetric = "
                       "false', or 'Plane stress = false'.");
    if (plane_stress && projected_volumetric_strain)
      throw InputError("subsection 'Finite element', parameter 'Volumetric "
                       "strain': in plane stress the volume change goes "
                       "into the strain normal to the plane, so nothing "
                       "locks; set 'Volumetric strain = full'.");
    if (!c.pairs.empty() && fe_degree > 2)
      throw InputError("subsection 'Finite element', parameter 'Degree': "
                       "contact supports Q1 and Q2 slave and master faces; "
                       "set 'Degree = 1' or '2' when 'Contact/Number of "
                       "contact pairs' > 0 (Q3 is available without "
                       "contact).");
    if (!c.pairs.empty() && linear_solver.type == LinearSolverType::cg)
      throw InputError("subsection 'Linear solver', parameter 'Type': contact "
                       "systems (u | lambda | Lambda) are unsymmetric "
                       "saddle-point systems, which CG cannot solve; set "
                       "'Type = GMRES' (block preconditioner) or 'direct' "
                       "when 'Contact/Number of contact pairs' > 0.");
    for (unsigned int k = 0; k < c.pairs.size(); ++k)
      {
        const auto       &p = c.pairs[k];
        const std::string where =
          "subsection 'Contact/Pair " + std::to_string(k + 1) + "'";
        if (p.slave_ids.empty())
          throw InputError(where + ", parameter 'Slave boundary id': give "
                                   "the boundary id(s) of the slave surface.");
        if (p.master_is_body())
          {
            if (p.master_ids.empty())
              throw InputError(where + ", parameter 'Master boundary id': "
                                       "Master = body needs the boundary "
                                       "id(s) of the master surface.");
            for (const auto id : p.master_ids)
              if (std::count(p.slave_ids.begin(), p.slave_ids.end(), id))
                throw InputError(
                  where + ": boundary id " + std::to_string(id) +
                  " is both slave and master. The slave and master surfaces "
                  "must be different boundaries (of different bodies).");
          }
        else
          check_obstacle_motion(p, where, dim);
      }
  }


  // ------------------------------------------------------------ File reading
  namespace
  {
    // The subsection path that is open at line @p line_no of @p text.
    std::string
    subsection_at_line(const std::string &text, const unsigned int line_no)
    {
      std::istringstream       in(text);
      std::vector<std::string> stack;
      std::string              line;
      for (unsigned int n = 1; n < line_no && std::getline(in, line); ++n)
        {
          line = Utilities::trim(line.substr(0, line.find('#')));
          if (line.rfind("subsection ", 0) == 0)
            stack.push_back(Utilities::trim(line.substr(11)));
          else if (line == "end" && !stack.empty())
            stack.pop_back();
        }
      std::string path;
      for (const auto &s : stack)
        path += (path.empty() ? "" : "/") + s;
      return path.empty() ? "top level" : "subsection '" + path + "'";
    }

    // A 'set' of an entry that an earlier line of the same subsection set
    // already: ParameterHandler takes the second silently, which hides a
    // pasted block or a forgotten edit. Names both lines (by @p origins
    // where the text was assembled from included files).
    void
    check_duplicate_entries(const std::string              &text,
                            const std::string              &source,
                            const std::vector<std::string> &origins)
    {
      const auto where = [&](const unsigned int n) {
        return n >= 1 && n <= origins.size() ?
                 origins[n - 1] :
                 source + ", line " + std::to_string(n);
      };
      std::istringstream                  in(text);
      std::vector<std::string>            stack;
      std::map<std::string, unsigned int> first;
      std::string                         line;
      for (unsigned int n = 1; std::getline(in, line); ++n)
        {
          line = Utilities::trim(line.substr(0, line.find('#')));
          if (line.rfind("subsection ", 0) == 0)
            stack.push_back(Utilities::trim(line.substr(11)));
          else if (line == "end" && !stack.empty())
            stack.pop_back();
          else if (line.rfind("set ", 0) == 0 &&
                   line.find('=') != std::string::npos)
            {
              std::string path;
              for (const auto &s : stack)
                path += s + "/";
              const std::string entry =
                Utilities::trim(line.substr(4, line.find('=') - 4));
              const auto [it, added] = first.emplace(path + entry, n);
              if (!added)
                throw InputError(
                  "Error in " + where(n) + " (" + subsection_at_line(text, n) +
                  "): the entry '" + entry +
                  "' is set a second time (first in " + where(it->second) +
                  "). Keep one of the two lines.");
            }
        }
    }


    // Entries removed when their choice was decided (one default per
    // choice, doc/theory.md): what the run does instead.
    const std::pair<const char *, const char *> removed[] = {
      {"Penalty",
       "the penalty law went; contact is always the augmented Lagrangian "
       "law."},
      {"Threshold coupling",
       "the friction rows are weighted by the pressure of the Newton "
       "iterate, held: no K_fc (doc/theory.md 3.2)."},
      {"Release extrapolation", "release extrapolation is always on."},
      {"Pairing at status changes",
       "the pairing is renewed between Newton solves only."},
      {"Statuses",
       "the integration-point rules decide the statuses per multiplier "
       "node on meshed masters (the nodal rule and rigid obstacles: one "
       "law per node)."},
      {"Friction threshold",
       "the friction threshold is always the current contact pressure "
       "(Newton on the threshold)."},
      {"Freeze after cycles",
       "a contact point is frozen after 3 status cycles in one Newton "
       "solve."},
      {"Segment order",
       "the mortar rule always uses the order exact for flat faces."},
      {"Normal",
       "the contact normal is always the master's (the slave and average "
       "normals failed action = reaction and gap checks)."},
      {"Write VTU",
       "the VTU files are written by the postprocessor 'visualization': "
       "list it in 'Output/Postprocessors' (it is in the default list) or "
       "leave it out."},
      {"Force balance tolerance",
       "the balance of the contact forces is checked by 'Action-reaction "
       "tolerance' in the same subsection (action = reaction of each "
       "pair), and the support reactions by the force balance of the "
       "bodies, which every run checks."},
      {"Friction status",
       "stick and slip are always decided per multiplier node on meshed "
       "masters (the former 'Friction status = node'); the nodal rule and "
       "rigid obstacles keep one law per node."},
      {"Stagnation tolerance",
       "the round-off floor of Newton's residual is computed from the size "
       "of its terms; 'Newton/Relative tolerance' and 'Newton/Absolute "
       "tolerance' set the convergence."},
      {"Geometric linearisation",
       "frictionless rigid obstacles are always linearised in Newton "
       "(projection, normal and curvature at every iterate); frictional "
       "pairs and meshed masters are paired again by the geometric loop."}};
    // Entries that moved to another subsection.
    const std::pair<const char *, const char *> moved[] = {
      {"Body force",
       "it is set per material now: move the line into subsection "
       "'Materials/Material k' of each material it acts on."},
      {"Obstacle point",
       "a rigid obstacle reads its data from its own subsection of "
       "'Contact/Pair k': 'Point' in subsection 'Plane', 'Centre' in "
       "'Sphere', 'Axis point' in 'Cylinder'. Move the line there."},
      {"Obstacle normal",
       "it is 'Outward normal' in subsection 'Contact/Pair k/Plane' now: "
       "move the line there."}};
    // Entries of 'Geometry/Body k' that moved into the shape's subsection.
    const char *const shape_entries[] = {"Lower corner",
                                         "Upper corner",
                                         "Subdivisions",
                                         "Centre",
                                         "Radius",
                                         "Inner radius",
                                         "Segment",
                                         "Length",
                                         "Mesh file",
                                         "Boundary id map",
                                         "Manifold",
                                         "Manifold boundary ids",
                                         "Manifold axis"};
    const char *const shape_entries_moved =
      "a shape reads its entries from its own subsection of 'Geometry/Body "
      "k', named after it: 'Lower corner', 'Upper corner' and "
      "'Subdivisions' in 'Block'; 'Centre', 'Radius', 'Inner radius' and "
      "'Segment' in 'Ball segment' or 'Cylinder segment' (with 'Length' "
      "and 'Axial subdivisions', the former 'Subdivisions'); 'Mesh file', "
      "'Boundary id map' and the 'Manifold' entries in 'File' (a file's "
      "'Centre' is 'Manifold centre'). Move the line there.";
    // Subsections that moved.
    const std::pair<const char *, const char *> moved_subsections[] = {
      {"Reference solution",
       "its entries are read by the postprocessor 'reference checks' "
       "now, from its own subsection 'Output/Reference checks': move the "
       "block into subsection 'Output' and rename it 'Reference "
       "checks'."}};


    // Turn deal.II's parse exception into one message naming line and
    // subsection, with a hint for the cases users hit most.
    std::string
    explain_parse_error(const ExceptionBase            &e,
                        const std::string              &text,
                        const std::string              &source,
                        const std::vector<std::string> &origins)
    {
      std::ostringstream info;
      e.print_info(info);
      std::string message = info.str();
      // print_info() indents and wraps; put it on one line.
      message = std::regex_replace(message, std::regex("\\s+"), " ");
      message = Utilities::trim(message);

      std::smatch m;
      std::string where = source;
      if (std::regex_search(message, m, std::regex("Line <(\\d+)>")))
        {
          const unsigned int line_no = std::stoi(m[1]);
          where = (line_no >= 1 && line_no <= origins.size() ?
                     origins[line_no - 1] :
                     source + ", line " + std::string(m[1])) +
                  " (" + subsection_at_line(text, line_no) + ")";
        }
      message = std::regex_replace(message,
                                   std::regex("Line <\\d+> of file <[^>]*>: "),
                                   "");
      // Never the content of the line: an included file may not be a
      // parameter file at all (include /etc/passwd).
      message = std::regex_replace(message,
                                   std::regex("The line <[^\n]*?> could not"),
                                   "This line could not");
      for (const auto &[name, where_now] : moved_subsections)
        if (message.find("no such subsection to be entered: " +
                         std::string(name)) != std::string::npos)
          return "Error in " + where + ": the subsection '" + name +
                 "' moved: " + where_now;
      for (const auto &[name, where_now] : moved)
        if (message.find("No entry with name <" + std::string(name) + ">") !=
            std::string::npos)
          return "Error in " + where + ": the entry '" + name +
                 "' moved: " + where_now;
      if (std::regex_search(where,
                            std::regex("subsection 'Geometry/Body \\d+'\\)$")))
        for (const char *name : shape_entries)
          if (message.find("No entry with name <" + std::string(name) + ">") !=
              std::string::npos)
            return "Error in " + where + ": the entry '" + name +
                   "' moved: " + shape_entries_moved;
      std::string hint;
      for (const auto &[name, instead] : removed)
        if (message.find("No entry with name <" + std::string(name) + ">") !=
            std::string::npos)
          return "Error in " + where + ": the entry '" + name +
                 "' was removed: " + instead + " Delete the line.";
      if (message.find("No entry with name") != std::string::npos ||
          message.find("has not been declared") != std::string::npos ||
          message.find("No such subsection") != std::string::npos ||
          message.find("not been declared") != std::string::npos)
        hint =
          " Check the spelling against 'signorini --print-parameters'; "
          "numbered subsections (Body k, Material k, Dirichlet k, "
          "Neumann k, Pair k) must not exceed their 'Number of ...' entry.";
      else if (message.find("does not match the given pattern") !=
               std::string::npos)
        hint = message.find("named Dimension") != std::string::npos ?
                 " Set Dimension = 2 (plane strain) or 3." :
                 " Change the value to one the pattern allows.";
      return "Error in " + where + ": " + message + hint;
    }

    Parameters
    parse_text(const std::string              &text,
               const std::string              &source,
               ParameterHandler               &prm,
               const std::vector<std::string> &origins   = {},
               const std::string              &directory = ".")
    {
      check_parameter_text(text, source);
      check_duplicate_entries(text, source, origins);
      // Pre-pass: only the counts and the plug-in libraries, ignoring
      // everything else.
      Counts counts;
      {
        ParameterHandler pre;
        pre.declare_entry("Dimension", "2", Patterns::Anything());
        pre.declare_entry(shared_libraries_entry, "", Patterns::Anything());
        pre.enter_subsection("Geometry");
        pre.declare_entry("Number of bodies", "1", Patterns::Integer(1, 16));
        pre.leave_subsection();
        pre.enter_subsection("Materials");
        pre.declare_entry("Number of materials", "1", Patterns::Integer(1, 64));
        pre.leave_subsection();
        pre.enter_subsection("Boundary conditions");
        pre.declare_entry("Number of Dirichlet conditions",
                          "1",
                          Patterns::Integer(0, 64));
        pre.declare_entry("Number of Neumann conditions",
                          "0",
                          Patterns::Integer(0, 64));
        pre.leave_subsection();
        pre.enter_subsection("Contact");
        pre.declare_entry("Number of contact pairs",
                          "0",
                          Patterns::Integer(0, 64));
        pre.leave_subsection();
        try
          {
            pre.parse_input_from_string(text, "", true);
          }
        catch (const ExceptionBase &e)
          {
            throw InputError(explain_parse_error(e, text, source, origins));
          }
        // Loaded before the declarations: their plug-ins' names and
        // subsections are declared with the library's.
        load_shared_libraries(Utilities::split_string_list(
                                pre.get(shared_libraries_entry)),
                              directory);
        pre.enter_subsection("Geometry");
        counts.n_bodies = pre.get_integer("Number of bodies");
        pre.leave_subsection();
        pre.enter_subsection("Materials");
        counts.n_materials = pre.get_integer("Number of materials");
        pre.leave_subsection();
        pre.enter_subsection("Boundary conditions");
        counts.n_dirichlet = pre.get_integer("Number of Dirichlet conditions");
        counts.n_neumann   = pre.get_integer("Number of Neumann conditions");
        pre.leave_subsection();
        pre.enter_subsection("Contact");
        counts.n_pairs = pre.get_integer("Number of contact pairs");
        pre.leave_subsection();
      }

      Parameters::declare_parameters(prm, counts);
      try
        {
          prm.parse_input_from_string(text, "", false);
        }
      catch (const ExceptionBase &e)
        {
          throw InputError(explain_parse_error(e, text, source, origins));
        }
      check_numbered_subsections(text, counts, source);
      Parameters parameters;
      parameters.parse_parameters(prm, counts);
      return parameters;
    }
  } // namespace


  namespace
  {
    // The directory of @p filename ("." for a bare name).
    std::string
    directory_of(const std::string &filename)
    {
      const auto slash = filename.find_last_of('/');
      return slash == std::string::npos ? "." : filename.substr(0, slash);
    }

    // ParameterHandler's 'include <file>' lines replaced by the file's text,
    // recursively, with relative paths taken from the directory of the file
    // that includes it (as 'Mesh file'; ParameterHandler itself would take
    // them from the working directory). @p origins gets "file 'f', line n"
    // for every line of the result, for messages.
    std::string
    expand_includes(const std::string        &text,
                    const std::string        &filename,
                    std::vector<std::string> &origins,
                    const unsigned int        depth = 0)
    {
      std::istringstream in(text);
      std::string        line, result;
      for (unsigned int n = 1; std::getline(in, line); ++n)
        {
          const std::string where =
            "parameter file '" + filename + "', line " + std::to_string(n);
          const std::string code =
            Utilities::trim(line.substr(0, line.find('#')));
          if (code.rfind("include", 0) != 0 ||
              (code.size() > 7 && !std::isspace(code[7])))
            {
              result += line + "\n";
              origins.push_back(where);
              continue;
            }
          std::string name = Utilities::trim(code.substr(7));
          if (name.empty())
            throw InputError(where + ": 'include' needs a file name.");
          if (depth >= 8)
            throw InputError(where + ": 'include' nested deeper than 8 "
                                     "files (does a file include itself?).");
          if (name[0] != '/')
            name = directory_of(filename) + "/" + name;
          std::ifstream included(name);
          if (!included || std::filesystem::is_directory(name))
            throw InputError(where + ": cannot read the included file '" +
                             name +
                             "'. Relative paths start at the directory of "
                             "the file that includes it.");
          std::stringstream buffer;
          buffer << included.rdbuf();
          check_parameter_text(buffer.str(), "included file '" + name + "'");
          result += expand_includes(buffer.str(), name, origins, depth + 1);
        }
      return result;
    }
  } // namespace


  Parameters
  read_parameters(const std::string &filename, ParameterHandler &prm)
  {
    if (std::filesystem::is_directory(filename))
      throw InputError("'" + filename +
                       "' is a directory, not a parameter file. Give the "
                       "path of a .prm file.");
    std::ifstream in(filename);
    if (!in)
      throw InputError("Cannot open the parameter file '" + filename +
                       "'. Give the path of an existing .prm file.");
    std::stringstream buffer;
    buffer << in.rdbuf();
    const std::string source = "parameter file '" + filename + "'";
    check_parameter_text(buffer.str(), source);
    std::vector<std::string> origins;
    const std::string text = expand_includes(buffer.str(), filename, origins);
    Parameters        parameters =
      parse_text(text, source, prm, origins, directory_of(filename));
    parameters.input_directory = directory_of(filename);
    parameters.input_file      = filename;
    return parameters;
  }


  Parameters
  read_parameters_from_string(const std::string &text, ParameterHandler &prm)
  {
    return parse_text(text, "parameter text", prm);
  }
} // namespace Signorini
