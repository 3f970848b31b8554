# plots/fmean.mk: the figures of `haff mc fmean` (docs/mc-fmean.md).  A fragment for the lead's
# plots/plots.mk (`include plots/fmean.mk` AFTER its own first target, so that it does not become
# the default goal, then add `fmean-plots` to that target); it
# also runs alone from the repository root: `make -f plots/fmean.mk` (bin/haff must be built).
#
# Targets
#   fmean-plots             all of the below
#   $(OUT)/fig4.png .svg .pdf  Fig. 4 redrawn: two dimers at contact for a/d = $(FIG4_A), the
#                           allowed contact-angle range marked   (data: $(OUT)/fig4.dat)
#   $(OUT)/fmean.png .svg   <f>(a/d) and D_e(a/d) for the heuristic, exclusion and collision
#                           models over a/d = $(FMEAN_SCAN)      (data: $(OUT)/fmean.tsv)
#   fmean-clean             removes those files
# Variables (override on the command line): HAFF, OUT, FIG4_A, FMEAN_SCAN, FMEAN_SAMPLES,
# FMEAN_SEED.  The scan takes ~10 s of one core with the defaults.  The data files depend on
# $(HAFF) only: after changing FIG4_A or FMEAN_SCAN, run fmean-clean first.
HAFF          ?= bin/haff
OUT           ?= plots/out
FIG4_A        ?= 1
FMEAN_SCAN    ?= 0.05:3:0.05
FMEAN_SAMPLES ?= 200000
FMEAN_SEED    ?= 1
GNUPLOT       ?= gnuplot

.PHONY: fmean-plots fmean-clean
fmean-plots: $(OUT)/fig4.png $(OUT)/fig4.svg $(OUT)/fig4.pdf $(OUT)/fmean.png $(OUT)/fmean.svg \
             $(OUT)/fmean.pdf
# haff's own Table I for the lower panel of fmean (plots.mk sets it; alone: none)
FMEAN_T1 ?=

$(OUT)/fig4.dat: $(HAFF)
	@mkdir -p $(@D)
	$(HAFF) mc fmean --a $(FIG4_A) --fig4-data > $@.tmp && mv $@.tmp $@

$(OUT)/fig4.png $(OUT)/fig4.svg $(OUT)/fig4.pdf &: $(OUT)/fig4.dat plots/fig4.gp plots/style.gp
	$(GNUPLOT) -e "data='$<'; a=$(FIG4_A); outbase='$(OUT)/fig4'" plots/fig4.gp

$(OUT)/fmean.tsv: $(HAFF)
	@mkdir -p $(@D)
	$(HAFF) mc fmean --scan $(FMEAN_SCAN) --model all --samples $(FMEAN_SAMPLES) \
	  --seed $(FMEAN_SEED) > $@.tmp && mv $@.tmp $@

$(OUT)/fmean.png $(OUT)/fmean.svg $(OUT)/fmean.pdf &: $(OUT)/fmean.tsv plots/fmean.gp plots/style.gp $(FMEAN_T1)
	$(GNUPLOT) -e "data='$<'; t1='$(FMEAN_T1)'; outbase='$(OUT)/fmean'" plots/fmean.gp

fmean-clean:
	rm -f $(OUT)/fig4.dat $(OUT)/fig4.png $(OUT)/fig4.svg $(OUT)/fig4.pdf \
	      $(OUT)/fmean.tsv $(OUT)/fmean.png $(OUT)/fmean.svg $(OUT)/fmean.pdf
