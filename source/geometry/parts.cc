#include <signorini/geometry/parts.h>

#include <map>
#include <numeric>

namespace Signorini
{
  namespace Geometry
  {
    template <int dim>
    std::vector<unsigned int>
    coarse_parts(const Triangulation<dim> &tria, unsigned int &n_parts)
    {
      // Union-find over the vertices of the coarse cells.
      std::vector<unsigned int> parent(tria.n_vertices());
      std::iota(parent.begin(), parent.end(), 0);
      const auto root = [&](unsigned int v) {
        while (parent[v] != v)
          v = parent[v] = parent[parent[v]];
        return v;
      };
      for (auto cell = tria.begin(0); cell != tria.end(0); ++cell)
        for (const unsigned int v : cell->vertex_indices())
          parent[root(cell->vertex_index(v))] = root(cell->vertex_index(0));
      std::vector<unsigned int>            part(tria.n_cells(0));
      std::map<unsigned int, unsigned int> number;
      for (auto cell = tria.begin(0); cell != tria.end(0); ++cell)
        part[cell->index()] =
          number.emplace(root(cell->vertex_index(0)), number.size())
            .first->second;
      n_parts = number.size();
      return part;
    }


    template <int dim>
    unsigned int
    part_of(const typename Triangulation<dim>::cell_iterator &cell,
            const std::vector<unsigned int>                  &parts)
    {
      auto ancestor = cell;
      while (ancestor->level() > 0)
        ancestor = ancestor->parent();
      return parts[ancestor->index()];
    }


    template std::vector<unsigned int>
    coarse_parts<2>(const Triangulation<2> &, unsigned int &);
    template std::vector<unsigned int>
    coarse_parts<3>(const Triangulation<3> &, unsigned int &);
    template unsigned int
    part_of<2>(const Triangulation<2>::cell_iterator &,
               const std::vector<unsigned int> &);
    template unsigned int
    part_of<3>(const Triangulation<3>::cell_iterator &,
               const std::vector<unsigned int> &);
  } // namespace Geometry
} // namespace Signorini
