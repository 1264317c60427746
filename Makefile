# vdcloth: the two commands are `make run` and `make test` (see README.md).
JOBS ?= $(shell nproc)
SCENE ?= scenes/sheet-hang.json
OUT ?= out/sheet-hang

.PHONY: all deps build build-asan run test bench clean

all: build

deps:
	@scripts/install-deps.sh

build: deps
	cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DVDCLOTH_TESTS=OFF -DVDCLOTH_BENCH=ON
	cmake --build build -j $(JOBS)

build-asan: deps
	cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVDCLOTH_SANITIZE=ON -DVDCLOTH_TESTS=ON -DVDCLOTH_BENCH=OFF
	cmake --build build-asan -j $(JOBS)

run: build
	build/vdcloth run $(SCENE) --out $(OUT)

test: build build-asan
	ctest --test-dir build-asan --output-on-failure -j $(JOBS)

bench: build
	build/bench/vdcloth_bench

clean:
	rm -rf build build-asan
