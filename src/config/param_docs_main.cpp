// marsokhod-param-docs: prints docs/parameters.md from the parameter schema.
//   build/src/config/marsokhod-param-docs > docs/parameters.md
#include <iostream>

#include "config/param_docs.hpp"

int main() {
  std::cout << marsokhod::config::parameters_markdown();
  return std::cout.good() ? 0 : 1;
}
