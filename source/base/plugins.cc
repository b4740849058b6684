// The families' parameter declarations (plugins.h).
#include <signorini/base/plugins.h>

namespace Signorini
{
  namespace Plugins
  {
    namespace
    {
      // Written by the Declaration objects of the families (at load time),
      // read by declare().
      std::map<Family, Declare> &
      declarations()
      {
        static std::map<Family, Declare> table;
        return table;
      }
    } // namespace


    void
    declare(const Family family, ParameterHandler &prm)
    {
      const auto it = declarations().find(family);
      if (it != declarations().end())
        it->second(prm);
    }


    Declaration::Declaration(const Family family, const Declare &declare)
    {
      declarations()[family] = declare;
    }
  } // namespace Plugins
} // namespace Signorini
