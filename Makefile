# vdcloth: the two commands are `make run` and `make test` (see README.md).
JOBS ?= $(shell nproc)
# The main job: the solo dancer through the camera's view, first 175 frames (7 s: the travelling
# shot and the cut to the close-up at frame 150).
SCENE ?= scenes/solo-dancer.json
MODE ?= view
FRAMES ?= 175
OUT ?= out/solo-dancer

.PHONY: all deps configure build build-asan run test bench fuzz clean

all: build

deps:
	@scripts/install-deps.sh

# build/: Release, the simulator, the benchmarks and the scene tests (whole scenes at full speed).
# Every layer compiles as unity files of sixteen sources, in half the time of one object a source;
# the two run bit for bit the same, and their speeds in runs side by side differ by less than
# this machine's spread (bench/RESULTS.md, "A Release build with unity files").
configure:
	cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DVDCLOTH_TESTS=OFF -DVDCLOTH_SCENE_TESTS=ON -DVDCLOTH_BENCH=ON \
	  -DVDCLOTH_UNITY=ON -DVDCLOTH_UNITY_LAYERS=""

build: deps configure
	cmake --build build -j $(JOBS)

# build-asan/: the unit tests under AddressSanitizer and UndefinedBehaviorSanitizer, at -O1 with
# line tables only: enough for the reports' file and line, and it compiles in two thirds of the
# time -O2 takes, while the tests run as fast. Unity files (sixteen sources each) halve the
# layers' compile time again.
build-asan: deps
	cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
	  -DVDCLOTH_SANITIZE=ON -DVDCLOTH_UNITY=ON -DVDCLOTH_TESTS=ON -DVDCLOTH_SCENE_TESTS=OFF -DVDCLOTH_BENCH=OFF
	cmake --build build-asan -j $(JOBS)

run: deps configure
	cmake --build build -j $(JOBS) --target vdcloth
	build/vdcloth run $(SCENE) --mode $(MODE) --frames $(FRAMES) --out $(OUT)

# The tests need the simulator and the scene tests of build/ (not its benchmarks) and the unit
# tests of build-asan/. One ctest runs both trees' tests together (build-tests/ lists them), the
# long scene tests first (their COST, tests/CMakeLists.txt), so neither tree's last tests leave a
# core idle while the other's wait.
test: deps configure build-asan
	cmake --build build -j $(JOBS) --target vdcloth vdcloth_scene_tests
	@mkdir -p build-tests
	@printf 'subdirs("%s/build-asan")\nsubdirs("%s/build")\n' "$(CURDIR)" "$(CURDIR)" > build-tests/CTestTestfile.cmake
	ctest --test-dir build-tests --output-on-failure -j $(JOBS)

bench: build
	build/bench/vdcloth_bench

# build-fuzz/: the libFuzzer targets (fuzz/README.md), built by clang with every layer
# instrumented, each run FUZZ_SECONDS (default 15 minutes) from the corpus.
FUZZ_SECONDS ?= 900
fuzz:
	@scripts/install-deps.sh fuzz
	CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
	  -DVDCLOTH_FUZZ=ON -DVDCLOTH_TESTS=OFF -DVDCLOTH_SCENE_TESTS=OFF -DVDCLOTH_BENCH=OFF
	cmake --build build-fuzz -j $(JOBS)
	fuzz/run.sh build-fuzz $(FUZZ_SECONDS)

clean:
	rm -rf build build-asan build-fuzz build-tests
