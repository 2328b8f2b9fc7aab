/* XDMF 2 sidecar writer; layout tested with ParaView 5.11's "XDMF Reader"
 * (shared/notes/daemon-research.md section 4.6).  The whole file is regenerated
 * after each frame because the HDF DataItem dimensions carry the current frame
 * count; it is written to a temporary file and renamed so that a reader never
 * sees a half-written sidecar. */
#include "io/output/xdmf.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

/* Field names and paths come from our own table, but escape anyway so the
 * output stays well-formed XML whatever a future field is called. */
static void put_escaped(FILE *fp, const char *s)
{
    for (; *s; s++) {
        switch (*s) {
        case '&': fputs("&amp;", fp); break;
        case '<': fputs("&lt;", fp); break;
        case '>': fputs("&gt;", fp); break;
        case '"': fputs("&quot;", fp); break;
        default: fputc(*s, fp);
        }
    }
}

static const char *number_type(const struct tlsph_field *f, int *precision)
{
    switch (f->type) {
    case TLSPH_FLOAT64: *precision = 8; return "Float";
    case TLSPH_FLOAT32: *precision = 4; return "Float";
    case TLSPH_INT64: *precision = 8; return "Int";
    case TLSPH_INT32: *precision = 4; return "Int";
    }
    *precision = 8;
    return "Float";
}

static const char *attribute_type(int ncomp)
{
    switch (ncomp) {
    case 1: return "Scalar";
    case 3: return "Vector";
    case 6: return "Tensor6";
    }
    return NULL;
}

/* The full-size HDF DataItem of a field: [F, N(, C)] for frame fields, [N(, C)]
 * for reference fields (per_frame: every field is a frame field). */
static void put_hdf_item(FILE *fp, const struct tlsph_field *f, const char *h5_name, size_t n,
                         size_t nframes, int per_frame)
{
    int precision;
    const char *nt = number_type(f, &precision);
    per_frame |= f->kind == TLSPH_FIELD_FRAME;
    fputs("      <DataItem Dimensions=\"", fp);
    if (per_frame)
        fprintf(fp, "%zu ", nframes);
    fprintf(fp, "%zu", n);
    if (f->ncomp > 1)
        fprintf(fp, " %d", f->ncomp);
    fprintf(fp, "\" NumberType=\"%s\" Precision=\"%d\" Format=\"HDF\">", nt, precision);
    put_escaped(fp, h5_name);
    fputs(":/particles/solid/", fp);
    put_escaped(fp, f->name);
    if (per_frame)
        fputs("/value", fp);
    fputs("</DataItem>\n", fp);
}

/* Frame k of a frame field as a HyperSlab item: its first nk of n particles;
 * a reference field directly (per_frame: every field is a frame field). */
static void put_data(FILE *fp, const struct tlsph_field *f, const char *h5_name, size_t n,
                     size_t nframes, size_t k, size_t nk, int per_frame)
{
    if (f->kind != TLSPH_FIELD_FRAME && !per_frame) {
        put_hdf_item(fp, f, h5_name, n, nframes, 0);
        return;
    }
    if (f->ncomp > 1) {
        fprintf(fp,
                "     <DataItem ItemType=\"HyperSlab\" Dimensions=\"%zu %d\" Type=\"HyperSlab\">\n"
                "      <DataItem Dimensions=\"3 3\" Format=\"XML\">%zu 0 0  1 1 1  1 %zu %d</DataItem>\n",
                nk, f->ncomp, k, nk, f->ncomp);
    } else {
        fprintf(fp,
                "     <DataItem ItemType=\"HyperSlab\" Dimensions=\"%zu\" Type=\"HyperSlab\">\n"
                "      <DataItem Dimensions=\"3 2\" Format=\"XML\">%zu 0  1 1  1 %zu</DataItem>\n",
                nk, k, nk);
    }
    put_hdf_item(fp, f, h5_name, n, nframes, per_frame);
    fputs("     </DataItem>\n", fp);
}

int tlsph_xdmf_write(const char *xmf_path, const char *h5_name, size_t n, size_t nframes,
                     const double *times, const size_t *counts,
                     const struct tlsph_field *const *fields, size_t nfields)
{
    const int per_frame = counts != NULL;
    const struct tlsph_field *geometry = NULL;
    for (size_t i = 0; i < nfields && !geometry; i++)
        if (fields[i]->kind == TLSPH_FIELD_FRAME && strcmp(fields[i]->name, "position") == 0)
            geometry = fields[i];
    for (size_t i = 0; i < nfields && !geometry; i++)
        if (fields[i]->kind == TLSPH_FIELD_FRAME && fields[i]->ncomp == 3 &&
            strcmp(fields[i]->units, "m") == 0)
            geometry = fields[i];
    if (!geometry) {
        errno = EINVAL;
        return -1;
    }

    char tmp[4096];
    if ((size_t)snprintf(tmp, sizeof tmp, "%s.tmp", xmf_path) >= sizeof tmp) {
        errno = ENAMETOOLONG;
        return -1;
    }
    FILE *fp = fopen(tmp, "w");
    if (!fp)
        return -1;

    fputs("<?xml version=\"1.0\" ?>\n"
          "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
          "<Xdmf Version=\"2.0\">\n"
          " <Domain>\n"
          "  <Grid Name=\"solid\" GridType=\"Collection\" CollectionType=\"Temporal\">\n",
          fp);
    for (size_t k = 0; k < nframes; k++) {
        const size_t nk = counts ? counts[k] : n;
        fprintf(fp,
                "   <Grid Name=\"frame%zu\" GridType=\"Uniform\">\n"
                "    <Time Value=\"%.17g\"/>\n"
                "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"%zu\" "
                "NodesPerElement=\"1\"/>\n"
                "    <Geometry GeometryType=\"XYZ\">\n",
                k, times[k], nk);
        put_data(fp, geometry, h5_name, n, nframes, k, nk, per_frame);
        fputs("    </Geometry>\n", fp);
        for (size_t i = 0; i < nfields; i++) {
            const struct tlsph_field *f = fields[i];
            const char *at = attribute_type(f->ncomp);
            if (!at)
                continue;
            fputs("    <Attribute Name=\"", fp);
            put_escaped(fp, f->name);
            fprintf(fp, "\" AttributeType=\"%s\" Center=\"Node\">\n", at);
            put_data(fp, f, h5_name, n, nframes, k, nk, per_frame);
            fputs("    </Attribute>\n", fp);
        }
        fputs("   </Grid>\n", fp);
    }
    fputs("  </Grid>\n"
          " </Domain>\n"
          "</Xdmf>\n",
          fp);

    int failed = ferror(fp);
    int saved = errno;
    if (fclose(fp) != 0 && !failed) {
        failed = 1;
        saved = errno;
    }
    if (!failed && rename(tmp, xmf_path) != 0) {
        failed = 1;
        saved = errno;
    }
    if (failed) {
        remove(tmp);
        errno = saved ? saved : EIO;
        return -1;
    }
    return 0;
}
