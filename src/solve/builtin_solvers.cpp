// Every solver luxel ships, one line each. Adding a solver is one new file with its
// registerXxx function, and one line here (docs/extending.md).
namespace luxel {

class SolverRegistry;
void registerCpuProgressive(SolverRegistry&);  // solve/progressive_solver.cpp
void registerCpuGather(SolverRegistry&);       // solve/gather_solver.cpp
void registerCpuHierarchical(SolverRegistry&); // hierarchical/hierarchical_solver.cpp
void registerCpuIncremental(SolverRegistry&);          // dynamic/redistribution_solver.cpp
void registerCpuCrossRedistribution(SolverRegistry&);  // dynamic/redistribution_solver.cpp
void registerGlProgressive(SolverRegistry&);   // gl/gl_solvers.cpp
void registerGlGather(SolverRegistry&);        // gl/gl_solvers.cpp
void registerGlIncremental(SolverRegistry&);   // gl/gl_solvers.cpp
void registerGlCrossRedistribution(SolverRegistry&);  // gl/gl_solvers.cpp

void registerBuiltinSolvers(SolverRegistry& registry) {
  registerCpuProgressive(registry);
  registerCpuGather(registry);
  registerCpuHierarchical(registry);
  registerCpuIncremental(registry);
  registerCpuCrossRedistribution(registry);
  registerGlProgressive(registry);
  registerGlGather(registry);
  registerGlIncremental(registry);
  registerGlCrossRedistribution(registry);
}

}  // namespace luxel
