#ifndef signorini_material_history_h
#define signorini_material_history_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/quadrature_point_data.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/grid/tria.h>

#include <memory>
#include <vector>

/**
 * The committed history of the constitutive models at the bulk quadrature
 * points (Material::Interface::n_history_values()), kept per locally owned
 * cell in deal.II's CellDataStorage. Every point keeps the same number of
 * values, the largest any model of the run asks for (each model reads its
 * own leading ones), so that ContinuousQuadratureDataTransfer can project
 * them across refinement. Each point also keeps the values it had at the
 * start of the last converged (sub)step: adaptive refinement within a step
 * solves that sub-step again on the new mesh from there. Without a model
 * with history it holds nothing.
 */
namespace Signorini
{
  namespace Material
  {
    using namespace dealii;

    /** The history values of one quadrature point: committed at the last
     * converged (sub)step, and at its start. */
    struct PointHistory : public TransferableQuadraturePointData
    {
      std::vector<double> values;
      std::vector<double> at_start;

      unsigned int
      number_of_values() const override
      {
        return values.size() + at_start.size();
      }
      void
      pack_values(std::vector<double> &v) const override
      {
        v = values;
        v.insert(v.end(), at_start.begin(), at_start.end());
      }
      void
      unpack_values(const std::vector<double> &v) override
      {
        const auto half = v.begin() + v.size() / 2;
        values.assign(v.begin(), half);
        at_start.assign(half, v.end());
      }
    };

    template <int dim>
    class History
    {
    public:
      using CellIterator = typename Triangulation<dim>::cell_iterator;

      /** Zero history with @p n_values values at each point of
       * @p quadrature (the bulk rule, QGauss(degree + 1) of the displacement
       * element) of every locally owned active cell of @p triangulation
       * that has none yet; 0 values: nothing is kept. */
      void
      initialize(const Triangulation<dim> &triangulation,
                 const Quadrature<dim>    &quadrature,
                 const unsigned int        n_values);

      /** Before a new (sub)step is committed: its start values are the
       * committed ones. */
      void
      save_start();

      /** Back to the values at the start of the last converged (sub)step,
       * to solve it again. */
      void
      restore_start();

      /** Before Triangulation::execute_coarsening_and_refinement(): the
       * values go along (refinement and repartitioning; coarsening is not
       * supported by deal.II's transfer and is refused at input). Each cell's
       * values are the samples of a polynomial of the displacement degree
       * (FE_DGQ, as many coefficients as points), which the children of a
       * refined cell evaluate at their points; a cell that stays keeps its
       * values exactly. */
      void
      prepare_for_refinement(
        parallel::distributed::Triangulation<dim> &triangulation);

      /** After the refinement: the values on the new cells, and nothing kept
       * for cells that are no longer locally owned and active. */
      void
      finish_refinement();

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

    private:
      /** Calls @p f with the points of every locally owned active cell. */
      template <typename F>
      void
      for_each_cell(const F &f);

      const Triangulation<dim>                   *triangulation = nullptr;
      CellDataStorage<CellIterator, PointHistory> data;
      Quadrature<dim>                             rule;
      unsigned int                                n_values = 0;
      std::unique_ptr<parallel::distributed::
                        ContinuousQuadratureDataTransfer<dim, PointHistory>>
        transfer;
    };
  } // namespace Material
} // namespace Signorini

#endif
