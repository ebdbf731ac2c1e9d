# The two commands of the README:
#   make demo   install what is missing, build, run the whole pipeline on the
#               embedded procedural motions (no external data)
#   make test   install what is missing, build, run every test
# Other targets: build, install (PREFIX=/usr/local), package (the .deb in
# build/), bench, asan (sanitizer build + tests), fuzz (libFuzzer harnesses
# with ASan + UBSan in build-fuzz/, clang), check-cpu (the numerics tests
# under every instruction set this CPU allows x 1 and 2 threads), lopo (leave
# one performer out on ../shared/mocap-corpus into LOPO_OUT; PRESET=full for
# the full preset), clean.

BUILD    ?= build
JOBS     ?= $(shell nproc)
CMAKE_FLAGS ?=
DEMO_OUT ?= demo
PREFIX   ?= /usr/local
LOPO_OUT ?= lopo

.PHONY: deps build-deps configure build demo test check-cpu lopo install package bench asan fuzz clean

# Everything (tests, benchmarks, the package) / only what building ptnet needs.
deps:
	@./scripts/install-deps.sh
build-deps:
	@./scripts/install-deps.sh build

# Configures $(BUILD) (Ninja for a new one: it compiles every stage's files in
# parallel), and again each time: a package installed since (GoogleTest for
# the tests after `make demo`) is found then. Re-configuring takes seconds.
configure:
	cmake -S . -B $(BUILD) $(if $(wildcard $(BUILD)/CMakeCache.txt),,-G Ninja) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)

build: deps
	@$(MAKE) --no-print-directory configure
	cmake --build $(BUILD) -j $(JOBS)

# Only what the demo runs (ptnet and ptnet-torch), not the tests and benchmarks.
demo: build-deps
	@$(MAKE) --no-print-directory configure
	cmake --build $(BUILD) -j $(JOBS) --target ptnet
	./$(BUILD)/ptnet demo --out $(DEMO_OUT) --force

test: build
	cd $(BUILD) && ctest --output-on-failure --no-tests=error -j $(JOBS)

# scripts/check-numerics.sh: one line per instruction set x thread count.
check-cpu: build
	./scripts/check-numerics.sh $(BUILD)

# scripts/lopo.sh: 7 folds of simulate, train and evaluate (docs/lopo.md);
# resumable, so the same command continues an interrupted run.
lopo: deps
	@$(MAKE) --no-print-directory configure
	cmake --build $(BUILD) -j $(JOBS) --target ptnet
	PTNET=$(BUILD)/ptnet ./scripts/lopo.sh $(LOPO_OUT)

install: deps
	@$(MAKE) --no-print-directory configure
	cmake --build $(BUILD) -j $(JOBS) --target installables
	cmake --install $(BUILD) --prefix $(PREFIX)

package: deps
	@$(MAKE) --no-print-directory configure
	cmake --build $(BUILD) -j $(JOBS) --target installables
	cd $(BUILD) && cpack

bench: build
	./scripts/run-benchmarks.sh $(BUILD)

asan: deps
	cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPTNET_SANITIZE=ON -DPTNET_BUILD_BENCH=OFF -DPTNET_PYTHON=OFF
	cmake --build build-asan -j $(JOBS)
	cd build-asan && ctest --output-on-failure -L unit -j $(JOBS)

fuzz: deps
	PTNET_FUZZ_DEPS=1 ./scripts/install-deps.sh
	cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPTNET_FUZZ=ON \
	      -DPTNET_BUILD_TESTS=OFF -DPTNET_BUILD_BENCH=OFF -DPTNET_PYTHON=OFF
	cmake --build build-fuzz -j $(JOBS) --target fuzzers
	@echo "fuzzers in build-fuzz/fuzz/; seeds in tests/data/fuzz/ (README.md, Development)"

clean:
	rm -rf $(BUILD) build-asan build-fuzz
