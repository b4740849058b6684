// A faulty postprocessor plug-in (a module the stock `signorini` loads):
// its statistics column changes name after the first step, which the run
// must refuse with a message naming it
// (tests/bad_input/postprocessor_renamed_column.prm.in).
#include <signorini/postprocess/interface.h>

namespace Example
{
  using namespace dealii;
  using Signorini::Postprocess::CheckResult;

  template <int dim>
  class RenamedColumn : public Signorini::Postprocess::Interface<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &)
    {
    }

    std::vector<CheckResult>
    execute(const Signorini::Postprocess::StepData<dim> &data) override
    {
      data.statistics.add(data.step == 1 ? "first" : "second", data.time);
      return {};
    }
  };
} // namespace Example

SIGNORINI_REGISTER_POSTPROCESSOR(Example::RenamedColumn,
                                 "renamed column",
                                 "a faulty statistics column "
                                 "(tests/plugins/renamed_column.cc)")
