// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
// Hard case "Holes" of the stacked height-field ray caster: see StrataHeightFieldCases.cxx.
#include <string>
namespace strata_test
{
int RunHeightFieldCase(const std::string& name);
}
int TestHeightFieldHoles(int, char*[])
{
  return strata_test::RunHeightFieldCase("Holes");
}
