// `luxel solvers [--json]`: what the registry holds, each solver with its options.
#pragma once

namespace luxel::cli {

int listSolvers(bool json);

}  // namespace luxel::cli
