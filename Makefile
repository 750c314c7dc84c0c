# Thin wrapper over CMake. `make demo` and `make test` work on a fresh Debian 12 machine.
BUILD      ?= build
BUILD_ASAN ?= build-asan
BUILD_FUZZ ?= build-fuzz
FUZZ_SECONDS ?= 60
JOBS       ?= $(shell nproc)
CMAKE_ARGS ?=

.PHONY: deps configure build demo test asan fuzz fuzz-smoke bench bench-suite bench-peer bench-peer-room clean

deps:
	./scripts/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_ARGS)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	mkdir -p out
	./$(BUILD)/luxel render cornell -o out/cornell.exr -o out/cornell.png --stats out/cornell-stats.json

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

# The same tests under AddressSanitizer and UndefinedBehaviorSanitizer.
asan: deps
	cmake -S . -B $(BUILD_ASAN) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLUXEL_SANITIZE=ON $(CMAKE_ARGS)
	cmake --build $(BUILD_ASAN) -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --test-dir $(BUILD_ASAN) --output-on-failure -j $(JOBS) -LE slow -E '(^|/)Gl'
	# Mesa's GL driver is unloaded at exit holding allocations LeakSanitizer can only attribute to
	# an "unknown module", so the GL tests run with leak detection off and every other check on.
	ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --test-dir $(BUILD_ASAN) --output-on-failure -j $(JOBS) -LE slow -R '(^|/)Gl'

# libFuzzer harnesses (fuzz/) built with clang, ASan and UBSan, each run FUZZ_SECONDS (docs/fuzzing.md).
fuzz: deps
	CC=clang CXX=clang++ cmake -S . -B $(BUILD_FUZZ) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLUXEL_FUZZ=ON \
	  -DLUXEL_BUILD_TESTS=OFF -DLUXEL_BUILD_BENCH=OFF $(CMAKE_ARGS)
	cmake --build $(BUILD_FUZZ) -j $(JOBS) --target fuzz-mesh-obj fuzz-mesh-gltf fuzz-mesh-glb fuzz-mesh-ply \
	  fuzz-mesh-dae fuzz-mesh-fbx fuzz-scene-json fuzz-texture fuzz-cli
	./fuzz/run.sh $(BUILD_FUZZ) $(FUZZ_SECONDS)

# CI's short, seeded run of the harnesses over luxel's own parsers (fuzz/smoke.sh says why not Assimp's).
fuzz-smoke: deps
	CC=clang CXX=clang++ cmake -S . -B $(BUILD_FUZZ) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DLUXEL_FUZZ=ON \
	  -DLUXEL_BUILD_TESTS=OFF -DLUXEL_BUILD_BENCH=OFF $(CMAKE_ARGS)
	cmake --build $(BUILD_FUZZ) -j $(JOBS) --target fuzz-scene-json fuzz-texture fuzz-cli
	./fuzz/smoke.sh $(BUILD_FUZZ)

bench: build
	./$(BUILD)/luxel-bench --benchmark_min_time=0.5

# The seed scenes beside the seeds' published figures, with Embree's raw throughput and the
# error against cached references (docs/performance.md).
bench-suite: build
	mkdir -p out
	./$(BUILD)/luxel bench seeds --json out/bench-seeds.json

# luxel beside Blender Cycles on the Cornell box (needs blender and python3-numpy).
bench-peer: build
	./bench/peers/run_cornell.sh

bench-peer-room: build
	./bench/peers/run_room.sh

clean:
	rm -rf $(BUILD) $(BUILD_ASAN) $(BUILD_FUZZ) out
