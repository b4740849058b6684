#ifndef signorini_base_format_h
#define signorini_base_format_h

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

namespace Signorini
{
  namespace Postprocess
  {
    /**
     * A number for compared output and CSV files: scientific with @p digits
     * digits after the point; NaN and inf spelled out; values below 1e-300
     * (round-off of a zero) printed as 0 so that compared output does not
     * depend on the number of MPI ranks.
     */
    inline std::string
    format(const double value, const int digits = 6)
    {
      if (std::isnan(value))
        return "NaN";
      if (std::isinf(value))
        return value > 0 ? "inf" : "-inf";
      std::ostringstream s;
      s << std::scientific << std::setprecision(digits)
        << (std::abs(value) < 1e-300 ? 0. : value);
      return s.str();
    }
  } // namespace Postprocess
} // namespace Signorini

#endif
