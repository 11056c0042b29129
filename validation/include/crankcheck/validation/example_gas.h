#pragma once
/// @file
/// The working loads of the report's engines: example pressure tables and firing at the dead centres (report parts
/// `torque_split`, `offset` and `flywheel` use them).

#include "crankcheck/scene/gas.h"
#include "crankcheck/scene/mechanism.h"

namespace crankcheck::validation {

/// An example gauge-pressure table: a spark-ignition four-stroke cycle (peak 5.6 MPa at 20 degrees) or a slow
/// two-stroke crosshead diesel (peak 15 MPa at 10 degrees), with the given bore [m].
GasParams makeExampleGas(Cycle cycle, double bore);

/// `m` with `gas`, each cylinder firing at its own outer dead centre phi = -alpha_j (mod the cycle): with eqs
/// (8)-(11)'s phases an evenly spaced firing.
Mechanism withGasAtDeadCentres(const Mechanism& m, const GasParams& gas);

}  // namespace crankcheck::validation
