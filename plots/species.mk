# plots/species.mk: the temperature ratio of binary disk mixtures (issue 29; included by
# plots/plots.mk; `make plots`).  scenes/mixture-disks.ini (SP_N light + SP_N heavy disks of one
# size at area fraction SP_ETA) for each heavy mass in SP_MASSES (light: m = 1) and each alpha in
# SP_ALPHAS, seeds SP_SEEDS, to SP_CPD cpd; `haff haff-fit --by-species` of each ensemble.
#   $(OUT)/species.png .svg .pdf  left: T_i/T of both species against m_heavy/m_light, runs
#                            (± standard error over the seeds) and Garzo-Dufty's Maxwellian
#                            approximation (lines); right: run/theory - 1 in %, ±3 % band
#   data: $(OUT)/data/species.tsv, one block per alpha: m_ratio alpha T_light T_light_err
#   th_light T_heavy T_heavy_err th_heavy; runs in $(OUT)/data/species/  (~60 s of one core)
# Also on its own (the test does: tests/test_species.c, species_figure):
#   make -f plots/species.mk OUT=DIR HAFF=bin/haff SP_MASSES='1 2' ... DIR/species.png
OUT       ?= plots/out
DATA      ?= $(OUT)/data
HAFF      ?= bin/haff
GNUPLOT   ?= gnuplot
SP_MASSES ?= 1 1.5 2 3 4 5
SP_ALPHAS ?= 0.7 0.8 0.95
SP_SEEDS  ?= 1 2 3 4
SP_N      ?= 300
SP_ETA    ?= 0.02
SP_CPD    ?= 60
SP_DIR    := $(DATA)/species-n$(SP_N)-eta$(SP_ETA)-c$(SP_CPD)

.PHONY: species-plots
species-plots: $(OUT)/species.png $(OUT)/species.svg $(OUT)/species.pdf

sp_db = $(SP_DIR)/m$(1)-al$(2).db
# one database per (mass, alpha) holding its seeds (written as .tmp, moved when complete)
define SP_RUN
$(call sp_db,$(1),$(2)): scenes/mixture-disks.ini $(HAFF)
	@mkdir -p $$(@D) && rm -f $$@.tmp
	@echo "run  $$@"
	@for s in $(SP_SEEDS); do $(HAFF) run scenes/mixture-disks.ini --quiet --seed $$$$s \
	  --set system.area_fraction=$(SP_ETA) --set species.light.count=$(SP_N) \
	  --set species.heavy.count=$(SP_N) --set species.heavy.m=$(1) \
	  --set species.light.alpha=$(2) --set species.heavy.alpha=$(2) \
	  --set run.stop_cpd=$(SP_CPD) -o $$@.tmp || exit 1; done
	@mv $$@.tmp $$@
endef
$(foreach m,$(SP_MASSES),$(foreach al,$(SP_ALPHAS),$(eval $(call SP_RUN,$(m),$(al)))))

# haff-fit --by-species of each database: its light and heavy rows side by side
$(OUT)/data/species.tsv: $(foreach m,$(SP_MASSES),$(foreach al,$(SP_ALPHAS),$(call sp_db,$(m),$(al)))) $(HAFF)
	@mkdir -p $(@D)
	{ printf 'm_ratio\talpha\tT_light\tT_light_err\tth_light\tT_heavy\tT_heavy_err\tth_heavy\n'; \
	  first=1; for al in $(SP_ALPHAS); do \
	    [ $$first = 1 ] || printf '\n\n'; first=0; \
	    for m in $(SP_MASSES); do \
	      $(HAFF) haff-fit $(SP_DIR)/m$$m-al$$al.db --by-species 2>/dev/null | \
	      awk -F'\t' -v m=$$m -v al=$$al '$$4 == "light" { l = $$6 "\t" $$7 "\t" $$9 } \
	        $$4 == "heavy" { h = $$6 "\t" $$7 "\t" $$9 } END { print m "\t" al "\t" l "\t" h }'; \
	    done; done; } > $@.tmp && mv $@.tmp $@

$(OUT)/species.png $(OUT)/species.svg $(OUT)/species.pdf &: $(OUT)/data/species.tsv plots/species.gp plots/style.gp
	$(GNUPLOT) -e "in='$<'; alphas='$(SP_ALPHAS)'; n=$(SP_N); eta=$(SP_ETA); seeds=$(words $(SP_SEEDS)); outbase='$(OUT)/species'" plots/species.gp

# plots/out/README.md lists this build's numbers (plots/scripts/readme.sh)
$(OUT)/README.md: $(OUT)/data/species.tsv
