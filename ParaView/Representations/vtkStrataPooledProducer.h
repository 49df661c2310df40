// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
/**
 * @class   vtkStrataPooledProducer
 * @brief   A trivial producer that says which page pool its data came from.
 *
 * Strata's mappers page from a pool when their input's connection is marked
 * vtkPagePoolProtocol::PAGE_POOL and its data names a pool (the identity in its field data).
 * Inside ParaView a representation gets a copy of the reader's output, past ParaView's own
 * pipeline, with the reader's mark gone but the field data kept. The representations hand
 * their mappers the data through this producer, which marks its output PAGE_POOL at every
 * information pass when the data names a pool, so a pool opened in ParaView is paged by the
 * mapper and never read whole. A time series needs nothing more: the identity names the step
 * shown and every step's pool, so the mapper pages the step ParaView's time selects and
 * prefetches the next one in playback order.
 */
#ifndef vtkStrataPooledProducer_h
#define vtkStrataPooledProducer_h

#include "StrataParaViewModule.h" // For export macro
#include "vtkPagePoolProtocol.h"  // For the pool's identity
#include "vtkTrivialProducer.h"

#include <string> // For std::string
#include <vector> // For std::vector

class STRATAPARAVIEW_EXPORT vtkStrataPooledProducer : public vtkTrivialProducer
{
public:
  static vtkStrataPooledProducer* New();
  vtkTypeMacro(vtkStrataPooledProducer, vtkTrivialProducer);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Sets the output and reads the pool it names, if any (vtkPagePoolProtocol::GetIdentity).
  void SetOutput(vtkDataObject* output) override;

  /// The pool behind the output ("" when none) and its layer.
  const char* GetPoolFileName() const { return this->Pool.FileName.c_str(); }
  int GetPoolLayer() const { return this->Pool.Layer; }
  /// Of a time series: the step shown (0 without one) and every step's pool (empty without).
  int GetPoolTimeStep() const { return this->Pool.TimeStep; }
  const std::vector<std::string>& GetPoolSeries() const { return this->Pool.Series; }

  vtkTypeBool ProcessRequest(vtkInformation* request,
    vtkInformationVector** inInfo,
    vtkInformationVector* outInfo) override;

protected:
  vtkStrataPooledProducer() = default;
  ~vtkStrataPooledProducer() override = default;

private:
  vtkStrataPooledProducer(const vtkStrataPooledProducer&) = delete;
  void operator=(const vtkStrataPooledProducer&) = delete;

  vtkPagePoolProtocol::Identity Pool;
};

#endif
