// Strata: ray casting for very large subsurface data. BSD-3-Clause, see LICENSE.
// BenchVolume's report sub-mode (BenchVolumeReport.cxx): summary tables on stdout and the
// RMS-vs-time plot as `png`, from the CSV `csv` the other sub-modes wrote.
#ifndef BenchVolumeReport_h
#define BenchVolumeReport_h

#include <string> // For std::string

int Report(const std::string& csv, const std::string& png);

#endif
