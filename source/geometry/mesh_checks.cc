#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/reference_cell.h>
#include <deal.II/numerics/rtree.h>

#include <signorini/geometry/mesh_checks.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <map>
#include <numeric>
#include <regex>
#include <set>
#include <sstream>

namespace Signorini
{
  namespace Geometry
  {
    namespace
    {
      // ------------------------------------------------------- cell types
      // "16 triangles and 4 quadrilaterals" from counts per kind.
      std::string
      count_list(const std::map<std::string, unsigned long> &counts)
      {
        std::string  text;
        unsigned int i = 0;
        for (const auto &[kind, n] : counts)
          {
            text += (i == 0                 ? "" :
                     i + 1 == counts.size() ? " and " :
                                              ", ") +
                    std::to_string(n) + " " + kind;
            ++i;
          }
        return text;
      }

      [[noreturn]] void
      refuse_cells(const std::string &where,
                   const std::string &found,
                   const unsigned int dim,
                   const std::string &how_to_convert)
      {
        throw InputError(where + ": the mesh has " + found +
                         ". Signorini computes on first-order " +
                         (dim == 2 ? "quadrilaterals" : "hexahedra") +
                         " only (Dimension = " + std::to_string(dim) + "). " +
                         how_to_convert);
      }

      // What to change in Gmsh: recombine and subdivide simplices, wedges
      // and pyramids into quadrilaterals or hexahedra (@p recombine), mesh
      // with first-order elements (@p higher_order).
      std::string
      gmsh_advice(const unsigned int dim,
                  const bool         recombine,
                  const bool         higher_order)
      {
        std::string advice = "Convert the mesh in Gmsh: ";
        if (recombine)
          advice += std::string("add 'Mesh.RecombineAll = 1;' and "
                                "'Mesh.SubdivisionAlgorithm = ") +
                    (dim == 2 ? "1;' to the .geo file (every cell split "
                                "into quadrilaterals)" :
                                "2;' to the .geo file (every cell split "
                                "into hexahedra)");
        if (higher_order)
          advice += std::string(recombine ? " and " : "") +
                    "set 'Mesh.ElementOrder = 1;' (first-order elements)";
        return advice + ", then mesh again (or mesh structured regions with "
                        "'Transfinite' and 'Recombine').";
      }

      // Gmsh element types by number (the MSH format's table); the ones a
      // mesh of Signorini may hold are points (15), lines (1),
      // quadrilaterals (3) and, in 3D, hexahedra (5).
      std::string
      gmsh_type_name(const int type)
      {
        static const std::map<int, std::string> names = {
          {2, "triangles"},
          {3, "quadrilaterals"},
          {4, "tetrahedra"},
          {5, "hexahedra"},
          {6, "prisms (wedges)"},
          {7, "pyramids"},
          {8, "second-order lines"},
          {9, "6-node triangles"},
          {10, "9-node quadrilaterals"},
          {11, "10-node tetrahedra"},
          {12, "27-node hexahedra"},
          {13, "18-node prisms"},
          {14, "14-node pyramids"},
          {16, "8-node quadrilaterals"},
          {17, "20-node hexahedra"},
          {18, "15-node prisms"},
          {19, "13-node pyramids"}};
        const auto it = names.find(type);
        return it != names.end() ?
                 it->second :
                 "elements of Gmsh type " + std::to_string(type);
      }

      // Elements per Gmsh type in an ASCII .msh text (formats 1, 2 and 4);
      // empty if the text is not one (GridIn then says what is wrong).
      std::map<int, unsigned long>
      gmsh_element_types(const std::string &text)
      {
        std::istringstream in(text);
        std::string        line;
        double             version   = 1;
        int                file_type = 0;
        while (std::getline(in, line))
          {
            line = Utilities::trim(line);
            if (line == "$MeshFormat")
              {
                if (!(in >> version >> file_type) || file_type != 0)
                  return {};
              }
            else if (line == "$Elements" || line == "$ELM")
              {
                std::map<int, unsigned long> types;
                if (version < 4)
                  {
                    // n, then one line per element: number, type, ...
                    unsigned long n = 0;
                    if (!(in >> n))
                      return {};
                    for (unsigned long i = 0; i < n; ++i)
                      {
                        long number = 0;
                        int  type   = 0;
                        if (!(in >> number >> type))
                          return {};
                        ++types[type];
                        std::getline(in, line);
                      }
                    return types;
                  }
                // Blocks: entity dimension, entity tag, type, count, then
                // one line per element.
                unsigned long blocks = 0, n = 0, min_tag = 0, max_tag = 0;
                if (!(in >> blocks >> n >> min_tag >> max_tag))
                  return {};
                for (unsigned long b = 0; b < blocks; ++b)
                  {
                    int           entity_dim = 0, tag = 0, type = 0;
                    unsigned long count = 0;
                    if (!(in >> entity_dim >> tag >> type >> count))
                      return {};
                    types[type] += count;
                    std::getline(in, line);
                    for (unsigned long i = 0; i < count; ++i)
                      std::getline(in, line);
                  }
                return types;
              }
          }
        return {};
      }

      // A binary .msh ("$MeshFormat" then "version 1 size"), which deal.II's
      // stream reader does not read (it stops at a garbled token).
      bool
      gmsh_is_binary(const std::string &text)
      {
        std::istringstream in(text);
        std::string        line;
        double             version   = 0;
        int                file_type = 0;
        while (std::getline(in, line))
          if (Utilities::trim(line) == "$MeshFormat")
            return (in >> version >> file_type) && file_type == 1;
        return false;
      }

      // The structure of an ASCII .msh text that GridIn reports only by a
      // token it did not expect: the format version (1, 2 and 4 are
      // read), a section the file ends inside (a truncated file), a node
      // coordinate that is not a finite number. Messages name lines, not
      // what they hold.
      void
      check_gmsh_structure(const std::string &text, const std::string &where)
      {
        std::istringstream in(text);
        std::string        line, open;
        unsigned long      number = 0, open_line = 0;
        while (std::getline(in, line))
          {
            ++number;
            line = Utilities::trim(line);
            if (line.empty() || line[0] != '$')
              {
                if (open == "$Nodes" || open == "$NOD")
                  {
                    std::istringstream tokens(line);
                    std::string        token;
                    while (tokens >> token)
                      {
                        char        *end   = nullptr;
                        const double value = std::strtod(token.c_str(), &end);
                        if (end == token.c_str() || *end != '\0' ||
                            !std::isfinite(value))
                          throw InputError(
                            where + ": line " + std::to_string(number) +
                            ", in its node section, is not a list of finite "
                            "numbers (a coordinate that is NaN, infinite or "
                            "not a number). Export the mesh again.");
                      }
                  }
                else if (open == "$MeshFormat")
                  {
                    std::istringstream tokens(line);
                    double             version = 0;
                    if (tokens >> version && !(version >= 1 && version < 3) &&
                        !(version >= 4 && version < 5))
                      throw InputError(
                        where + ": Gmsh format version " +
                        Utilities::to_string(version) +
                        ", which deal.II's reader does not read. Save the "
                        "mesh in format 2.2 or 4.1 (ASCII).");
                  }
                continue;
              }
            if (line.compare(0, 4, "$End") == 0 || line == "$ENDNOD" ||
                line == "$ENDELM")
              open.clear();
            else if (open.empty())
              {
                open      = line;
                open_line = number;
              }
          }
        if (!open.empty())
          throw InputError(where +
                           ": the file ends inside the section that "
                           "starts at line " +
                           std::to_string(open_line) +
                           " (it has no end marker): the file is "
                           "truncated. Export the mesh again.");
      }

      void
      check_gmsh_cells(const std::string &text,
                       const unsigned int dim,
                       const std::string &where)
      {
        if (gmsh_is_binary(text))
          throw InputError(where +
                           ": a binary Gmsh file, which deal.II's reader "
                           "cannot read. Save the mesh as ASCII ('Mesh.Binary "
                           "= 0;', Gmsh's default).");
        check_gmsh_structure(text, where);
        std::map<std::string, unsigned long> all;
        bool recombine = false, higher_order = false;
        for (const auto &[type, n] : gmsh_element_types(text))
          {
            if (type == 15 || type == 1)
              continue;
            all[gmsh_type_name(type)] += n;
            // Second-order quadrilaterals, hexahedra and lines (8, 10, 12,
            // 16, 17) only need first-order elements; anything else also
            // needs recombining.
            higher_order = higher_order || type >= 8;
            recombine    = recombine ||
                        !(type == 3 || type == 5 || type == 8 || type == 10 ||
                          type == 12 || type == 16 || type == 17);
          }
        const bool hexahedra_in_2d = dim == 2 && all.count(gmsh_type_name(5));
        if (recombine || higher_order || hexahedra_in_2d)
          refuse_cells(where,
                       count_list(all),
                       dim,
                       hexahedra_in_2d && !recombine && !higher_order ?
                         "A mesh of hexahedra is a 3D mesh: set 'Dimension "
                         "= 3'." :
                         gmsh_advice(dim, recombine, higher_order));
      }

      // An Abaqus *ELEMENT block whose elements do not have 4 (2D) or 8
      // (3D) nodes: deal.II's reader takes the first 2^dim numbers of every
      // line as the vertices of a quadrilateral or hexahedron, whatever the
      // element type.
      void
      check_abaqus_cells(const std::string &text,
                         const unsigned int dim,
                         const std::string &where)
      {
        const unsigned int                   expected = dim == 2 ? 4 : 8;
        std::map<std::string, unsigned long> wrong;
        std::istringstream                   in(text);
        std::string                          line, header, element;
        bool                                 in_elements = false;
        while (std::getline(in, line))
          {
            line = Utilities::trim(line);
            if (!line.empty() && line[0] == '*')
              {
                std::string upper = line;
                std::transform(upper.begin(),
                               upper.end(),
                               upper.begin(),
                               [](unsigned char c) { return std::toupper(c); });
                in_elements = upper.compare(0, 8, "*ELEMENT") == 0 &&
                              upper.compare(0, 15, "*ELEMENT OUTPUT") != 0;
                header = line;
                continue;
              }
            if (!in_elements || line.empty())
              continue;
            // An element with many nodes continues after a trailing comma.
            element += line;
            if (line.back() == ',')
              continue;
            const auto fields = Utilities::split_string_list(element, ',');
            element.clear();
            const unsigned int nodes =
              std::count_if(fields.begin(),
                            fields.end(),
                            [](const auto &f) { return !f.empty(); }) -
              1;
            if (nodes != expected)
              ++wrong["elements with " + std::to_string(nodes) +
                      " nodes in the block '" + header + "'"];
          }
        if (!wrong.empty())
          refuse_cells(
            where,
            count_list(wrong),
            dim,
            "Export first-order quadrilaterals (4 nodes, e.g. CPE4, CPS4, "
            "CAX4) in 2D or hexahedra (8 nodes, e.g. C3D8, C3D8R) in 3D.");
      }
    } // namespace


    void
    check_mesh_file_cells(const std::string &text,
                          const std::string &extension,
                          const unsigned int dim,
                          const std::string &where)
    {
      if (extension == "msh")
        check_gmsh_cells(text, dim, where);
      else if (extension == "inp")
        check_abaqus_cells(text, dim, where);
    }


    template <int dim>
    void
    check_reference_cells(const Triangulation<dim> &tria,
                          const std::string        &where)
    {
      if (tria.all_reference_cells_are_hyper_cube())
        return;
      std::map<std::string, unsigned long> counts;
      for (const auto &cell : tria.active_cell_iterators())
        {
          const ReferenceCell r = cell->reference_cell();
          ++counts[r == ReferenceCells::Triangle      ? "triangles" :
                   r == ReferenceCells::Quadrilateral ? "quadrilaterals" :
                   r == ReferenceCells::Tetrahedron   ? "tetrahedra" :
                   r == ReferenceCells::Hexahedron    ? "hexahedra" :
                   r == ReferenceCells::Wedge         ? "wedges" :
                   r == ReferenceCells::Pyramid       ? "pyramids" :
                                                        r.to_string()];
        }
      refuse_cells(where,
                   count_list(counts),
                   dim,
                   gmsh_advice(dim, true, false));
    }


    std::string
    grid_in_diagnostics(const std::string &captured)
    {
      // The "Additional information" of each exception deal.II printed,
      // without its stack trace.
      std::string       text;
      const std::string key = "Additional information:";
      for (auto pos = captured.find(key); pos != std::string::npos;
           pos      = captured.find(key, pos + 1))
        {
               const auto end = captured.find("Stacktrace:", pos);
               text += " " + captured.substr(pos + key.size(),
                                        end == std::string::npos ?
                                               std::string::npos :
                                               end - pos - key.size());
        }
      return Utilities::trim(std::regex_replace(text, std::regex("\\s+"), " "));
    }


    // ------------------------------------------------------------- sizes
    std::string
    cell_estimate_text(const double cells, const Parameters &parameters)
    {
      // A large mesh has about one vertex per cell: dim degree^dim
      // displacement DoFs per cell.
      const double dofs = parameters.dimension *
                          std::pow(parameters.fe_degree, parameters.dimension) *
                          cells;
      std::ostringstream text;
      text << std::setprecision(3) << "about " << cells << " cells (about "
           << dofs
           << " displacement DoFs), more than 'Maximum number of cells' = "
           << parameters.geometry.maximum_cells;
      return text.str();
    }


    void
    check_global_refinements(const std::size_t n_coarse_cells,
                             const Parameters &parameters)
    {
      const unsigned int levels = parameters.geometry.global_refinements;
      const double       cells =
        n_coarse_cells * std::pow(2., parameters.dimension * levels);
      if (cells > parameters.geometry.maximum_cells)
        throw InputError(
          "subsection 'Geometry', parameter 'Global refinements': " +
          std::to_string(levels) + " global refinement(s) of the " +
          std::to_string(n_coarse_cells) + " coarse cell(s) would make " +
          cell_estimate_text(cells, parameters) +
          " (each refinement multiplies the cells by 2^Dimension = " +
          std::to_string(1u << parameters.dimension) +
          "). Lower 'Global refinements' (or the coarse mesh), or raise "
          "'Geometry/Maximum number of cells' if the machine has the "
          "memory.");
    }


    void
    check_body_cells(const double       cells,
                     const std::string &where,
                     const std::string &entry,
                     const Parameters  &parameters)
    {
      if (cells > parameters.geometry.maximum_cells)
        throw InputError(where + ": the body would have " +
                         cell_estimate_text(cells, parameters) + ". Lower '" +
                         entry +
                         "', or raise 'Geometry/Maximum number of cells' if "
                         "the machine has the memory.");
    }


    template <int dim>
    double
    cells_after_refinement(
      const parallel::distributed::Triangulation<dim> &triangulation)
    {
      double flagged = 0;
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned() && cell->refine_flag_set())
          ++flagged;
      flagged = Utilities::MPI::sum(flagged, triangulation.get_communicator());
      return static_cast<double>(triangulation.n_global_active_cells()) +
             ((1u << dim) - 1) * flagged;
    }


    template <int dim>
    void
    check_local_refinement(
      const parallel::distributed::Triangulation<dim> &triangulation,
      const unsigned int                               cycle,
      const Parameters                                &parameters)
    {
      const double n_cells = cells_after_refinement(triangulation);
      if (n_cells > parameters.geometry.maximum_cells)
        throw InputError(
          "subsection 'Geometry', parameter 'Local refinements': local "
          "refinement cycle " +
          std::to_string(cycle + 1) + " of " +
          std::to_string(parameters.geometry.local_refinements) +
          " would make " + cell_estimate_text(n_cells, parameters) +
          ". Lower 'Local refinements' or 'Global refinements', shrink "
          "'Refinement region', or raise 'Maximum number of cells' if the "
          "machine has the memory.");
    }


    // ----------------------------------------------------- contact bodies
    template <int dim>
    void
    add_mesh_parts(const Triangulation<dim> &tria,
                   const unsigned int        body,
                   std::vector<MeshPart>    &parts)
    {
      // Union-find over the vertices: cells sharing a vertex are one part.
      std::vector<unsigned int> parent(tria.n_vertices());
      std::iota(parent.begin(), parent.end(), 0u);
      const auto root = [&](unsigned int v) {
        while (parent[v] != v)
          v = parent[v] = parent[parent[v]];
        return v;
      };
      for (const auto &cell : tria.active_cell_iterators())
        for (const unsigned int v : cell->vertex_indices())
          parent[root(cell->vertex_index(v))] = root(cell->vertex_index(0));

      std::map<unsigned int, unsigned int> part_of_root;
      for (const auto &cell : tria.active_cell_iterators())
        part_of_root.emplace(root(cell->vertex_index(0)), part_of_root.size());
      const std::size_t first = parts.size();
      parts.resize(first + part_of_root.size());
      for (unsigned int p = 0; p < part_of_root.size(); ++p)
        {
          parts[first + p].body    = body;
          parts[first + p].part    = p;
          parts[first + p].n_parts = part_of_root.size();
        }
      for (const auto &cell : tria.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            parts[first + part_of_root[root(cell->vertex_index(0))]]
              .boundary_ids.insert(face->boundary_id());
    }


    namespace
    {
      std::string
      part_name(const MeshPart &part)
      {
        return "Body " + std::to_string(part.body + 1) +
               (part.n_parts > 1 ? " (part " + std::to_string(part.part + 1) +
                                     " of the " + std::to_string(part.n_parts) +
                                     " unconnected parts of its mesh)" :
                                   "");
      }
    } // namespace


    void
    check_contact_surfaces(const ContactParameters     &contact,
                           const std::vector<MeshPart> &parts)
    {
      for (unsigned int k = 0; k < contact.pairs.size(); ++k)
        {
          const auto       &pair = contact.pairs[k];
          const std::string where =
            "subsection 'Contact/Pair " + std::to_string(k + 1) + "'";
          // The parts the slave surface touches, each with a slave id on it.
          std::map<unsigned int, types::boundary_id> slave_parts;
          for (const auto id : pair.slave_ids)
            for (unsigned int i = 0; i < parts.size(); ++i)
              if (parts[i].boundary_ids.count(id))
                slave_parts.emplace(i, id);
          if (slave_parts.size() > 1)
            {
              const auto a = slave_parts.begin(), b = std::next(a);
              throw InputError(
                where +
                ", parameter 'Slave boundary id': the slave surface must lie "
                "on one body, but boundary id " +
                std::to_string(a->second) + " is on " +
                part_name(parts[a->first]) + " and boundary id " +
                std::to_string(b->second) + " on " +
                part_name(parts[b->first]) +
                " (bodies are the connected parts of the mesh). Give each "
                "slave body its own contact pair ('Number of contact "
                "pairs'), and bodies distinct boundary ids ('Boundary ids', "
                "or 'Boundary id map' for a mesh file).");
            }
          if (!pair.master_is_body() || slave_parts.empty())
            continue;
          const auto &slave = *slave_parts.begin();
          for (const auto id : pair.master_ids)
            if (parts[slave.first].boundary_ids.count(id))
              throw InputError(
                where + ", parameter 'Master boundary id': boundary id " +
                std::to_string(id) + " is on " + part_name(parts[slave.first]) +
                ", the body of the slave surface (slave boundary id " +
                std::to_string(slave.second) +
                "). The master surface must be on another body: contact of "
                "a body with itself is not supported.");
        }
    }


    template <int dim>
    std::string
    overlap_warning(const std::vector<const Triangulation<dim> *> &bodies,
                    const std::vector<MeshPart>                   &parts,
                    const ContactParameters                       &contact)
    {
      const auto body_with = [&](const std::vector<types::boundary_id> &ids) {
        for (const auto id : ids)
          for (const auto &part : parts)
            if (part.boundary_ids.count(id))
              return static_cast<int>(part.body);
        return -1;
      };
      std::set<std::pair<unsigned int, unsigned int>> joined;
      for (const auto &pair : contact.pairs)
        if (pair.master_is_body())
          {
            const int s = body_with(pair.slave_ids);
            const int m = body_with(pair.master_ids);
            if (s >= 0 && m >= 0)
              joined.insert(std::minmax<unsigned int>(s, m));
          }
      const MappingQ1<dim> mapping;
      for (unsigned int a = 0; a < bodies.size(); ++a)
        {
          using Cell = typename Triangulation<dim>::active_cell_iterator;
          std::vector<std::pair<BoundingBox<dim>, Cell>> boxes;
          for (const auto &cell : bodies[a]->active_cell_iterators())
            boxes.emplace_back(cell->bounding_box(), cell);
          const auto tree = pack_rtree(boxes);
          for (unsigned int b = 0; b < bodies.size(); ++b)
            {
              if (a == b || joined.count(std::minmax(a, b)))
                continue;
              const auto &used = bodies[b]->get_used_vertices();
              const auto &x    = bodies[b]->get_vertices();
              for (unsigned int v = 0; v < x.size(); ++v)
                {
                  if (!used[v])
                    continue;
                  std::vector<std::pair<BoundingBox<dim>, Cell>> hits;
                  tree.query(boost::geometry::index::intersects(x[v]),
                             std::back_inserter(hits));
                  for (const auto &hit : hits)
                    try
                      {
                        const Point<dim> p =
                          mapping.transform_real_to_unit_cell(hit.second, x[v]);
                        bool inside = true;
                        for (unsigned int d = 0; d < dim; ++d)
                          inside = inside && p[d] > 1e-6 && p[d] < 1 - 1e-6;
                        if (!inside)
                          continue;
                        std::ostringstream s;
                        s << "Warning: body " << b + 1 << " overlaps body "
                          << a + 1 << " (its vertex (";
                        for (unsigned int d = 0; d < dim; ++d)
                          s << (d > 0 ? ", " : "") << x[v][d];
                        s << ") lies inside it) and no contact pair joins "
                             "them: they pass through each other. Give them "
                             "a 'Contact/Pair k', or move one.";
                        return s.str();
                      }
                    catch (const ExceptionBase &)
                      {
                        // No unit point: the vertex is not in this cell.
                      }
                }
            }
        }
      return "";
    }


    template std::string
    overlap_warning<2>(const std::vector<const Triangulation<2> *> &,
                       const std::vector<MeshPart> &,
                       const ContactParameters &);
    template std::string
    overlap_warning<3>(const std::vector<const Triangulation<3> *> &,
                       const std::vector<MeshPart> &,
                       const ContactParameters &);
    template void
    check_reference_cells<2>(const Triangulation<2> &, const std::string &);
    template void
    check_reference_cells<3>(const Triangulation<3> &, const std::string &);
    template void
    check_local_refinement<2>(const parallel::distributed::Triangulation<2> &,
                              const unsigned int,
                              const Parameters &);
    template void
    check_local_refinement<3>(const parallel::distributed::Triangulation<3> &,
                              const unsigned int,
                              const Parameters &);
    template double
    cells_after_refinement<2>(const parallel::distributed::Triangulation<2> &);
    template double
    cells_after_refinement<3>(const parallel::distributed::Triangulation<3> &);
    template void
    add_mesh_parts<2>(const Triangulation<2> &,
                      const unsigned int,
                      std::vector<MeshPart> &);
    template void
    add_mesh_parts<3>(const Triangulation<3> &,
                      const unsigned int,
                      std::vector<MeshPart> &);
  } // namespace Geometry
} // namespace Signorini
