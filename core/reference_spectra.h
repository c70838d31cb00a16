#pragma once
/// Measured spectral tables compiled into the program (the same numbers ship as CSV in
/// data/spectra/ with their sources): the extraterrestrial solar spectrum and the absorption
/// cross section of ozone, both in 10 nm steps from 360 to 830 nm.
#include "core/csv_table.h"

namespace kasumi {

/// Extraterrestrial solar spectral irradiance at 1 au, W/(m² nm): the ASTM G173-03 ETR column
/// averaged over the bins [360, 370), ..., [830, 840) nm (Bruneton 2017,
/// precomputed_atmospheric_scattering, demo.cc kSolarIrradiance), each mean tabulated at its
/// bin centre 365, 375, ..., 835 nm, with flat half bins to 360 and 840 nm (50 rows).
const WavelengthTable& solar_irradiance_astm_g173();

/// Trapezoidal integral of the ASTM G173-03 ETR column (0.5 nm steps below 400 nm, 1 nm above)
/// over [360, 840] nm, W/m², computed from the standard's own table: the total the 10 nm bin
/// means above must reproduce (sum of the 48 means x 10 nm, the integral of the table).
inline constexpr double kAstmG173EtrIntegral360To840 = 745.27;

/// Absorption cross section of ozone at 233 K, m² per molecule (Serdyuchenko et al. 2014,
/// Atmos. Meas. Tech. 7, 625; IUP Bremen data averaged over 10 nm bins by Bruneton 2017, demo.cc
/// kOzoneCrossSection), tabulated at lambda = 360, 370, ..., 830 nm.
const WavelengthTable& ozone_cross_section_233k();

/// One Dobson unit: 2.687e20 molecules per m² (0.01 mm of the pure gas at 273.15 K and 1 atm;
/// WMO; the value Bruneton 2017 uses).
inline constexpr double kDobsonUnitPerM2 = 2.687e20;

/// Ozone column of Bruneton 2017's Earth atmosphere, Dobson units.
inline constexpr double kDefaultOzoneColumnDu = 300.0;

}  // namespace kasumi
