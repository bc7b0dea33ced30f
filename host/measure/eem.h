#pragma once
// Excitation–emission matrices as docs/formats.md#measurement-csv lays them out: first row a label
// then the excitation wavelengths λi; each further row an emission wavelength λo then the readings
// R(λo; λi). Also read from JASCO 3-D exports, whose first XYDATA row holds the excitation
// wavelengths.
#include <Eigen/Dense>
#include <string>
#include <vector>

namespace kasha {

struct ExcitationEmissionMatrix {
  std::string source;
  std::vector<double> ex_nm;  // λi, increasing (columns)
  std::vector<double> em_nm;  // λo, increasing (rows)
  Eigen::MatrixXd value;      // rows λo, columns λi

  bool same_grid(const ExcitationEmissionMatrix& other) const;
};

// Throws kasha::Error naming the file and the row/column of any bad cell.
ExcitationEmissionMatrix read_eem(const std::string& path);

}  // namespace kasha
