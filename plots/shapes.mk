# plots/shapes.mk: the shapes figure of issue 18 (included by plots/plots.mk; `make plots`).
# Cooling gases of disks, dimers, trimers (linear, bent, triangle) and asymmetric dimers
# (build/plots/shapes, plots/shapes.c: one run per shape, N bodies at area fraction ETA,
# alpha SHAPES_ALPHA to SHAPES_CPD cpd), and the MC <f> of each shape under the collision model
# (`haff mc fmean --disks`) against the mean f of the run's collisions.
#   $(OUT)/shapes.png .svg .pdf  left: E/E0 against (1 - alpha^2) cpd with exp(-x/2) (disks) and
#                            exp(-x/3) (any turning body: D_e = 3); right: <f> engine - MC
#   data: $(OUT)/data/shapes.tsv (runs), $(OUT)/data/shapes_f.tsv (shape, engine <f> and error,
#   MC collision <f> and error)                                       (~20 s of one core)
SHAPES_BIN     ?= build/plots/shapes
SHAPES_N       ?= 500
SHAPES_ETA     ?= 0.05
SHAPES_ALPHA   ?= 0.95
SHAPES_CPD     ?= 80
SHAPES_SAMPLES ?= 200000

.PHONY: shapes-plots
shapes-plots: $(OUT)/shapes.png $(OUT)/shapes.svg $(OUT)/shapes.pdf

$(OUT)/data/shapes.tsv: $(SHAPES_BIN)
	@mkdir -p $(@D)
	$(SHAPES_BIN) $(SHAPES_N) $(SHAPES_ETA) $(SHAPES_ALPHA) $(SHAPES_CPD) 1 > $@.tmp && mv $@.tmp $@

$(OUT)/data/shapes_f.tsv: $(OUT)/data/shapes.tsv $(HAFF)
	grep '^# disks' $< | while read -r _ _ name spec; do \
	  eng=$$(awk -v n="$$name" '$$2 == "f" && $$3 == n { print $$4 "\t" $$5 }' $<); \
	  mc=$$($(HAFF) mc fmean --disks "$$spec" --model collision --samples $(SHAPES_SAMPLES) | \
	        awk -F'\t' 'NR == 2 { print $$3 "\t" $$4 }'); \
	  printf '%s\t%s\t%s\n' "$$name" "$$eng" "$$mc"; \
	done > $@.tmp && mv $@.tmp $@

$(OUT)/shapes.png $(OUT)/shapes.svg $(OUT)/shapes.pdf &: $(OUT)/data/shapes.tsv $(OUT)/data/shapes_f.tsv plots/shapes.gp plots/style.gp
	$(GNUPLOT) -e "in='$<'; fin='$(OUT)/data/shapes_f.tsv'; alpha=$(SHAPES_ALPHA); outbase='$(OUT)/shapes'" plots/shapes.gp
