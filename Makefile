# The two commands of the quick start: `make demo` and `make test`. Both install what is missing first.
BUILD ?= build
MINIMAL_BUILD ?= build-minimal
JOBS  ?= $(shell nproc)

.PHONY: setup setup-paraview build demo test test-minimal bench peers-bench clean
setup:
	@bash tools/setup.sh

# ParaView with its Python (about 440 MB): the test of the XDMF sidecars runs with it (skipped without).
setup-paraview:
	@bash tools/setup.sh --paraview

build: setup
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

demo: build
	@mkdir -p out
	$(BUILD)/mesocrack run scenes/lattice_tension_2d.toml -o out/demo.h5
	$(BUILD)/mesocrack summary out/demo.h5
	$(BUILD)/mesocrack report out/demo.h5

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# No rigid-cell family, no MPI: builds the tests in $(MINIMAL_BUILD), runs the build_options label (MINIMAL_CTEST= all).
MINIMAL_CTEST ?= -L build_options
test-minimal: setup
	@cmake -S . -B $(MINIMAL_BUILD) -DCMAKE_BUILD_TYPE=Release -DMESOCRACK_RIGID_CELL=OFF -DMESOCRACK_MPI=OFF >/dev/null
	@cmake --build $(MINIMAL_BUILD) -j $(JOBS) --target mesocrack_tests
	cd $(MINIMAL_BUILD) && ctest --output-on-failure --no-tests=error -j $(JOBS) $(MINIMAL_CTEST)

bench: build
	$(BUILD)/benchmarks/throughput

# The peers (Yade; installed with --install, never a dependency) against ours on the shared specimen, same session.
PEERS_ARGS ?= --install --specimens n10k --rounds 2
peers-bench: build
	/usr/bin/python3 benchmarks/peers/peers_bench.py --build $(BUILD) $(PEERS_ARGS)

clean:
	rm -rf $(BUILD) $(MINIMAL_BUILD) out
