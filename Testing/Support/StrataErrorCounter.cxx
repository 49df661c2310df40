// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
#include "StrataErrorCounter.h"

#include "vtkAlgorithm.h"
#include "vtkExecutive.h"

namespace strata_test
{
void ErrorCounter::Execute(vtkObject*, unsigned long event, void* data)
{
  (event == vtkCommand::ErrorEvent ? this->Errors : this->Warnings)++;
  // Keep the first message (the algorithm's own; the executive's "returned failure" follows it),
  // without VTK's "ERROR: In file, line" prefix line.
  if (this->First.empty() && data)
  {
    this->First = static_cast<const char*>(data);
    const size_t body = this->First.find("): ");
    this->First = body == std::string::npos ? this->First : this->First.substr(body + 3);
    this->First = this->First.substr(0, this->First.find_last_not_of("\n") + 1);
  }
}

void ErrorCounter::Watch(vtkAlgorithm* algorithm)
{
  for (vtkObject* o :
    { static_cast<vtkObject*>(algorithm), static_cast<vtkObject*>(algorithm->GetExecutive()) })
  {
    o->AddObserver(vtkCommand::ErrorEvent, this);
    o->AddObserver(vtkCommand::WarningEvent, this);
  }
}

void ErrorCounter::Reset()
{
  this->Errors = this->Warnings = 0;
  this->First.clear();
}
}
