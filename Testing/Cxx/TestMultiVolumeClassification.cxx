// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
// Case "Classification" of the multi-volume ray caster: see StrataMultiVolumeCases.cxx.
#include <string>
namespace strata_test
{
int RunMultiVolumeCase(const std::string& name);
}
int TestMultiVolumeClassification(int, char*[])
{
  return strata_test::RunMultiVolumeCase("Classification");
}
