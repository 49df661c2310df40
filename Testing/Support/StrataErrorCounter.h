// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
//
// The readers' tests' error counter (StrataTestingIO: it watches vtkAlgorithm and its executive).
#ifndef StrataErrorCounter_h
#define StrataErrorCounter_h

#include "vtkCommand.h"

#include <string>

class vtkAlgorithm;

namespace strata_test
{
/// Counts ErrorEvent and WarningEvent of an algorithm and its executive, so that expected errors
/// neither print nor go unnoticed; keeps the first message without VTK's file/line prefix.
class ErrorCounter : public vtkCommand
{
public:
  static ErrorCounter* New() { return new ErrorCounter; }
  void Execute(vtkObject*, unsigned long event, void* data) override;
  void Watch(vtkAlgorithm* algorithm);
  void Reset();
  int Errors = 0;
  int Warnings = 0;
  std::string First;
};
}

#endif
