#include <deal.II/fe/fe_dgq.h>

#include <signorini/material/history.h>

#include <cmath>

namespace Signorini
{
  namespace Material
  {
    template <int dim>
    void
    History<dim>::initialize(const Triangulation<dim> &tria,
                             const Quadrature<dim>    &quadrature,
                             const unsigned int        n)
    {
      triangulation = &tria;
      n_values      = n;
      rule          = quadrature;
      if (n_values == 0)
        return;
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            // initialize() keeps the data of cells that have some.
            data.template initialize<PointHistory>(cell, rule.size());
            for (const auto &point : data.get_data(cell))
              if (point->values.empty())
                {
                  point->values.assign(n_values, 0.);
                  point->at_start.assign(n_values, 0.);
                }
          }
    }


    template <int dim>
    template <typename F>
    void
    History<dim>::for_each_cell(const F &f)
    {
      if (n_values == 0)
        return;
      for (const auto &cell : triangulation->active_cell_iterators())
        if (cell->is_locally_owned())
          for (const auto &point : data.get_data(cell))
            f(*point);
    }


    template <int dim>
    void
    History<dim>::save_start()
    {
      for_each_cell([](PointHistory &p) { p.at_start = p.values; });
    }


    template <int dim>
    void
    History<dim>::restore_start()
    {
      for_each_cell([](PointHistory &p) { p.values = p.at_start; });
    }


    template <int dim>
    void
    History<dim>::prepare_for_refinement(
      parallel::distributed::Triangulation<dim> &tria)
    {
      if (n_values == 0)
        return;
      // QGauss(p + 1) has (p + 1)^dim points: as many as FE_DGQ(p) has
      // coefficients, so the projection interpolates the samples.
      const unsigned int degree =
        std::lround(std::pow(rule.size(), 1. / dim)) - 1;
      transfer =
        std::make_unique<parallel::distributed::
                           ContinuousQuadratureDataTransfer<dim, PointHistory>>(
          FE_DGQ<dim>(degree), rule, rule);
      transfer->prepare_for_coarsening_and_refinement(tria, data);
    }


    template <int dim>
    void
    History<dim>::finish_refinement()
    {
      if (!transfer)
        return;
      // The new cells need their points before the transfer fills them.
      initialize(*triangulation, rule, n_values);
      transfer->interpolate();
      transfer.reset();
      for (const auto &cell : triangulation->cell_iterators())
        if (!cell->is_active() || !cell->is_locally_owned())
          data.erase(cell);
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
