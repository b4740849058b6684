// The shape 'file' (shapes/file.h): a mesh read by deal.II's GridIn.
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/manifold_lib.h>

#include <signorini/base/input_checks.h>
#include <signorini/base/parameter_helpers.h>
#include <signorini/geometry/mesh_checks.h>
#include <signorini/geometry/shapes/file.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace Signorini
{
  namespace Geometry
  {
    namespace Shapes
    {
      namespace
      {
        // Refuses a cell whose (multi)linear map is not orientation
        // preserving at every vertex: inverted or tangled (e.g. a bow-tie
        // quadrilateral from a wrong node order). deal.II's readers repair
        // cells that are merely inverted as a whole; a tangled cell would
        // run and give a wrong solution without any sign.
        template <int dim>
        void
        check_cells(const Triangulation<dim> &tria, const std::string &where)
        {
          for (const auto &cell : tria.active_cell_iterators())
            for (unsigned int corner = 0; corner < (1u << dim); ++corner)
              {
                // Edge vectors along the reference directions at this
                // corner (deal.II's lexicographic vertex numbering).
                Tensor<2, dim> J;
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    const Tensor<1, dim> e = cell->vertex(corner | (1u << d)) -
                                             cell->vertex(corner & ~(1u << d));
                    for (unsigned int r = 0; r < dim; ++r)
                      J[r][d] = e[r];
                  }
                if (determinant(J) > 1e-12 * std::pow(cell->diameter(), dim))
                  continue;
                std::ostringstream text;
                text << where << ": the cell with centre (" << cell->center()
                     << ") is inverted or tangled (its map from the reference "
                        "cell is not orientation preserving at vertex ("
                     << cell->vertex(corner)
                     << ")). Fix the node order or the node positions of "
                        "that element in the mesh.";
                throw InputError(text.str());
              }
        }


        // Refuses a curved face whose vertices are not equidistant from
        // the manifold's centre (sphere) or axis (cylinder: @p axis
        // nonzero), and an id that names no face: a wrong 'Manifold centre'
        // would otherwise bend the refined mesh out of shape.
        template <int dim>
        void
        check_curved_faces(const Triangulation<dim>              &tria,
                           const std::vector<types::boundary_id> &ids,
                           const Point<dim>                      &centre,
                           const Tensor<1, dim>                  &axis)
        {
          const auto distance = [&](const Point<dim> &p) {
            const Tensor<1, dim> r = p - centre;
            return (r - (r * axis) * axis).norm();
          };
          std::set<types::boundary_id> found;
          for (const auto &face : tria.active_face_iterators())
            if (face->at_boundary() &&
                std::find(ids.begin(), ids.end(), face->boundary_id()) !=
                  ids.end())
              {
                found.insert(face->boundary_id());
                double r_min = distance(face->vertex(0)), r_max = r_min;
                for (const auto v : face->vertex_indices())
                  {
                    r_min = std::min(r_min, distance(face->vertex(v)));
                    r_max = std::max(r_max, distance(face->vertex(v)));
                  }
                if (r_max - r_min <= 1e-5 * r_max)
                  continue;
                std::ostringstream text;
                text << "parameter 'Manifold boundary ids': the face with "
                        "centre ("
                     << face->center() << ") and boundary id "
                     << face->boundary_id() << " has vertices at distances "
                     << r_min << " to " << r_max << " from the manifold's "
                     << (axis.norm() > 0 ? "axis" : "centre")
                     << ", so it does not lie on one surface about it. Check "
                        "'Manifold centre' (in the file's coordinates)"
                     << (axis.norm() > 0 ? " and 'Manifold axis'" : "")
                     << ", or leave this id out.";
                throw InputError(text.str());
              }
          for (const auto id : ids)
            if (found.count(id) == 0)
              throw InputError("parameter 'Manifold boundary ids': no "
                               "boundary face of this body has the id " +
                               std::to_string(id) +
                               " (ids after 'Boundary id map').");
        }
      } // namespace


      template <int dim>
      void
      MeshFile<dim>::declare_parameters(ParameterHandler &prm)
      {
        prm.enter_subsection("File");
        prm.declare_entry("Mesh file",
                          "",
                          Patterns::FileName(),
                          "Gmsh (.msh) or Abaqus (.inp) mesh of first-order "
                          "quadrilaterals (2D) or hexahedra (3D). Relative "
                          "paths are taken from the directory of the "
                          "parameter file.");
        prm.declare_entry(
          "Boundary id map",
          "",
          Patterns::Map(Patterns::Integer(0, 255), Patterns::Integer(0, 255)),
          "Physical group (Gmsh tag / Abaqus surface number) -> boundary id, "
          "as 'tag: id, tag: id'. Tags not listed keep their number.");
        prm.declare_entry(
          "Manifold",
          "none",
          Patterns::Selection("none|sphere|cylinder"),
          "The exact surface that the faces with 'Manifold boundary ids' lie "
          "on, so that refinement (global, local, adaptive) puts new nodes on "
          "it; without it the flat faces of the file stay flat when refined. "
          "sphere: a sphere (2D: a circle) about 'Manifold centre'; cylinder "
          "(3D): about the line through 'Manifold centre' along 'Manifold "
          "axis'. Both are in the file's coordinates (before the body's "
          "'Shift' and 'Rotation angle').");
        prm.declare_entry(
          "Manifold boundary ids",
          "",
          Patterns::List(Patterns::Integer(0, 255), 0, 255, ","),
          "Boundary ids (after 'Boundary id map') of the "
          "faces on the 'Manifold' surface; each face's "
          "vertices must lie on one sphere (cylinder) about "
          "it.");
        prm.declare_entry("Manifold centre",
                          "0, 0, 0",
                          internal::point_pattern(),
                          "Centre of the 'Manifold' sphere, or a point of "
                          "the cylinder's axis [m].");
        prm.declare_entry("Manifold axis",
                          "0, 0, 1",
                          internal::point_pattern(),
                          "Direction of the axis of a 'Manifold = cylinder' "
                          "(3D; any length but 0).");
        prm.leave_subsection();
      }


      template <int dim>
      void
      MeshFile<dim>::parse_parameters(ParameterHandler  &prm,
                                      const std::string &input_directory)
      {
        prm.enter_subsection("File");
        name = prm.get("Mesh file");
        id_map.clear();
        for (const auto &entry :
             Utilities::split_string_list(prm.get("Boundary id map"), ','))
          {
            const auto kv = Utilities::split_string_list(entry, ':');
            id_map[Utilities::string_to_int(kv[0])] =
              Utilities::string_to_int(kv[1]);
          }
        manifold = prm.get("Manifold");
        const auto ids =
          internal::to_unsigned(prm.get("Manifold boundary ids"));
        manifold_ids.assign(ids.begin(), ids.end());
        try
          {
            manifold_centre =
              internal::parse_point<dim>(prm, "Manifold centre");
            if (manifold == "cylinder")
              manifold_axis =
                internal::parse_direction<dim>(prm, "Manifold axis");
          }
        catch (...)
          {
            prm.leave_subsection();
            throw;
          }
        prm.leave_subsection();

        if (name.empty())
          throw InputError("parameter 'Mesh file': give the name of a .msh "
                           "or .inp file.");
        path = name[0] == '/' ? name : input_directory + "/" + name;
        if (!std::ifstream(path) || std::filesystem::is_directory(path))
          throw InputError("parameter 'Mesh file': cannot open '" + path +
                           "'. Give an existing .msh or .inp file (relative "
                           "paths start at the parameter file's directory).");
        const std::string ext = path.substr(path.find_last_of('.') + 1);
        if (ext != "msh" && ext != "inp")
          throw InputError("parameter 'Mesh file': unknown extension '." + ext +
                           "'; use .msh or .inp.");
        if (manifold == "none" && !manifold_ids.empty())
          throw InputError("parameter 'Manifold boundary ids': it needs "
                           "'Manifold' (sphere or cylinder); remove it "
                           "otherwise.");
        if (manifold != "none" && manifold_ids.empty())
          throw InputError("parameter 'Manifold boundary ids': list the "
                           "boundary ids of the faces on the 'Manifold' "
                           "surface.");
        if (manifold == "cylinder" && dim == 2)
          throw InputError("parameter 'Manifold': cylinder is for 3D "
                           "meshes; a circle in 2D is 'sphere'.");
      }


      template <int dim>
      void
      MeshFile<dim>::read(Triangulation<dim> &tria) const
      {
        // Cell types are checked on the text first: GridIn reads triangles
        // and tetrahedra into cells the element loops cannot use, and
        // refuses others with a list that does not say what to do.
        std::stringstream buffer;
        buffer << std::ifstream(path).rdbuf();
        const std::string ext   = path.substr(path.find_last_of('.') + 1);
        const std::string where = "parameter 'Mesh file' (" + name + ")";
        check_mesh_file_cells(buffer.str(), ext, dim, where);
        std::istringstream text(buffer.str());
        GridIn<dim>        grid_in;
        grid_in.attach_triangulation(tria);
        // The Abaqus reader prints its inner exception (with a stack trace)
        // before it throws: kept for the message.
        CerrCapture diagnostics;
        try
          {
            if (ext == "msh")
              grid_in.read_msh(text);
            else
              grid_in.read_abaqus(text);
          }
        catch (const ExceptionBase &e)
          {
            std::ostringstream info;
            e.print_info(info);
            // What GridIn quotes of the file is left out: a 'Mesh file' may
            // be a link to any file.
            const std::regex  quoted("<[^<>\n]*>");
            const std::string said =
              std::regex_replace(info.str(), quoted, "(a line of the file)");
            const std::string more =
              std::regex_replace(grid_in_diagnostics(diagnostics.text()),
                                 quoted,
                                 "(a line of the file)");
            throw InputError("parameter 'Mesh file': GridIn could not read '" +
                             path + "': " + said +
                             (more.empty() ? "" : " (" + more + ")"));
          }
        check_reference_cells(tria, where);
        check_cells(tria, where);
      }


      template <int dim>
      void
      MeshFile<dim>::build(Triangulation<dim> &tria) const
      {
        read(tria);
        for (const auto &face : tria.active_face_iterators())
          if (face->at_boundary())
            {
              const auto it = id_map.find(face->boundary_id());
              if (it != id_map.end())
                face->set_boundary_id(it->second);
            }
      }


      template <int dim>
      unsigned int
      MeshFile<dim>::n_face_groups() const
      {
        return 0;
      }


      template <int dim>
      CurvedSurface<dim>
      MeshFile<dim>::curved_surface(const Triangulation<dim> &tria,
                                    const Placement<dim>     &placement) const
      {
        CurvedSurface<dim> curved;
        if (manifold == "none")
          return curved;
        check_curved_faces(tria, manifold_ids, manifold_centre, manifold_axis);
        curved.faces            = manifold_ids;
        const Point<dim> centre = placement(manifold_centre);
        if (manifold == "cylinder")
          curved.manifold = std::make_unique<CylindricalManifold<dim>>(
            placement.direction(manifold_axis), centre);
        else
          curved.manifold = std::make_unique<SphericalManifold<dim>>(centre);
        return curved;
      }

      template class MeshFile<2>;
      template class MeshFile<3>;
    } // namespace Shapes
  }   // namespace Geometry
} // namespace Signorini

SIGNORINI_REGISTER_SHAPE(Signorini::Geometry::Shapes::MeshFile,
                         "file",
                         "a Gmsh (.msh) or Abaqus (.inp) 'Mesh file' read by "
                         "deal.II's GridIn, its boundary and material ids "
                         "kept")
