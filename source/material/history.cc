#include <signorini/material/history.h>

namespace Signorini
{
  namespace Material
  {
    template <int dim>
    void
    History<dim>::initialize(const Triangulation<dim> &triangulation,
                             const Quadrature<dim>    &quadrature,
                             const unsigned int        n)
    {
      n_values = n;
      rule     = quadrature;
      if (n_values == 0)
        return;
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            // initialize() keeps the data of cells that have some.
            data.template initialize<PointHistory>(cell, rule.size());
            for (const auto &point : data.get_data(cell))
              if (point->values.empty())
                point->values.assign(n_values, 0.);
          }
    }


    template <int dim>
    ArrayView<const double>
    History<dim>::at(const CellIterator &cell,
                     const unsigned int  q,
                     const unsigned int  n) const
    {
      if (n == 0)
        return {};
      AssertIndexRange(n, n_values + 1);
      return ArrayView<const double>(data.get_data(cell)[q]->values.data(), n);
    }


    template <int dim>
    ArrayView<double>
    History<dim>::at(const CellIterator &cell,
                     const unsigned int  q,
                     const unsigned int  n)
    {
      if (n == 0)
        return {};
      AssertIndexRange(n, n_values + 1);
      return ArrayView<double>(data.get_data(cell)[q]->values.data(), n);
    }


    template <int dim>
    std::vector<ArrayView<const double>>
    History<dim>::on_cell(const CellIterator &cell, const unsigned int n) const
    {
      std::vector<ArrayView<const double>> views(rule.size());
      if (n == 0)
        return views;
      AssertIndexRange(n, n_values + 1);
      const auto values = data.get_data(cell);
      for (unsigned int q = 0; q < views.size(); ++q)
        views[q] = ArrayView<const double>(values[q]->values.data(), n);
      return views;
    }


    template <int dim>
    std::vector<ArrayView<double>>
    History<dim>::on_cell(const CellIterator &cell, const unsigned int n)
    {
      std::vector<ArrayView<double>> views(rule.size());
      if (n == 0)
        return views;
      AssertIndexRange(n, n_values + 1);
      const auto values = data.get_data(cell);
      for (unsigned int q = 0; q < views.size(); ++q)
        views[q] = ArrayView<double>(values[q]->values.data(), n);
      return views;
    }


    template <int dim>
    unsigned int
    History<dim>::nearest_point(const Point<dim> &unit_point) const
    {
      unsigned int nearest = 0;
      for (unsigned int q = 1; q < rule.size(); ++q)
        if (unit_point.distance_square(rule.point(q)) <
            unit_point.distance_square(rule.point(nearest)))
          nearest = q;
      return nearest;
    }


    template class History<2>;
    template class History<3>;
  } // namespace Material
} // namespace Signorini
