#ifndef signorini_material_history_h
#define signorini_material_history_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/quadrature_point_data.h>

#include <deal.II/grid/tria.h>

#include <vector>

/**
 * The committed history of the constitutive models at the bulk quadrature
 * points (Material::Interface::n_history_values()), kept per locally owned
 * cell in deal.II's CellDataStorage. Every point keeps the same number of
 * values, the largest any model of the run asks for (each model reads its
 * own leading ones), so that ContinuousQuadratureDataTransfer can project
 * them across refinement. Without a model with history it holds nothing.
 */
namespace Signorini
{
  namespace Material
  {
    using namespace dealii;

    /** The history values of one quadrature point. */
    struct PointHistory : public TransferableQuadraturePointData
    {
      std::vector<double> values;

      unsigned int
      number_of_values() const override
      {
        return values.size();
      }
      void
      pack_values(std::vector<double> &v) const override
      {
        v = values;
      }
      void
      unpack_values(const std::vector<double> &v) override
      {
        values = v;
      }
    };

    template <int dim>
    class History
    {
    public:
      using CellIterator = typename Triangulation<dim>::cell_iterator;

      /** Zero history with @p n_values values at each point of
       * @p quadrature (the bulk rule) of every locally owned active cell of
       * @p triangulation that has none yet; 0 values: nothing is kept. */
      void
      initialize(const Triangulation<dim> &triangulation,
                 const Quadrature<dim>    &quadrature,
                 const unsigned int        n_values);

      /** Some model keeps a history. */
      bool
      active() const
      {
        return n_values > 0;
      }

      /** The first @p n values of point @p q of @p cell (locally owned);
       * an empty view when @p n is 0. */
      ArrayView<const double>
      at(const CellIterator &cell,
         const unsigned int  q,
         const unsigned int  n) const;
      ArrayView<double>
      at(const CellIterator &cell, const unsigned int q, const unsigned int n);

      /** The first @p n values of every point of @p cell (locally owned),
       * indexed by quadrature point, from one lookup in the storage; empty
       * views when @p n is 0. For loops over all points of a cell. */
      std::vector<ArrayView<const double>>
      on_cell(const CellIterator &cell, const unsigned int n) const;
      std::vector<ArrayView<double>>
      on_cell(const CellIterator &cell, const unsigned int n);

      /** The bulk rule (its points on the reference cell). */
      const Quadrature<dim> &
      quadrature() const
      {
        return rule;
      }

      /** The quadrature point of the bulk rule nearest to @p unit_point
       * (for output at points that are not quadrature points). */
      unsigned int
      nearest_point(const Point<dim> &unit_point) const;

      /** The storage, for the transfer across refinement. */
      CellDataStorage<CellIterator, PointHistory> &
      storage()
      {
        return data;
      }

    private:
      CellDataStorage<CellIterator, PointHistory> data;
      Quadrature<dim>                             rule;
      unsigned int                                n_values = 0;
    };
  } // namespace Material
} // namespace Signorini

#endif
