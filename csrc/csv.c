/* CSV output: each number written as Python's repr writes a float (the shortest digits that read
 * back to the same double; fixed notation for decimal exponents -4 .. 15, else d.ddde+XX), so a
 * file is byte for byte what the csv module would write, about 30 times faster. The shortest
 * digits come from Ryu (Ulf Adams, vendored in third_party/ryu, Boost/Apache-2.0 licences). */
#include "ryu/d2s.c"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

#include "pysolver.h"

#define CSV_BUFFER (1 << 20)

static int copy_str(char* out, const char* s) {
  int n = 0;
  while (s[n]) {
    out[n] = s[n];
    n++;
  }
  return n;
}

/* Write f as Python's repr(float) does into out (at most 25 characters); return the length. */
static int format_double(double f, char* out) {
  const uint64_t bits = double_to_bits(f);
  const bool sign = (bits >> 63) != 0;
  const uint64_t mant = bits & ((1ull << DOUBLE_MANTISSA_BITS) - 1);
  const uint32_t ex = (uint32_t)((bits >> DOUBLE_MANTISSA_BITS) & 0x7ffu);
  if (ex == 0x7ffu) return copy_str(out, mant ? "nan" : sign ? "-inf" : "inf");
  if (ex == 0 && mant == 0) return copy_str(out, sign ? "-0.0" : "0.0");
  floating_decimal_64 v;
  if (!d2d_small_int(mant, ex, &v)) v = d2d(mant, ex);
  uint64_t m = v.mantissa;
  int e = v.exponent;
  while (m % 10 == 0) {
    m /= 10;
    e++;
  }
  /* the digits of m, most significant first */
  char dig[20];
  int nd = 0;
  for (uint64_t q = m; q > 0; q /= 10) dig[nd++] = (char)('0' + q % 10);
  for (int i = 0; i < nd / 2; i++) {
    char c = dig[i];
    dig[i] = dig[nd - 1 - i];
    dig[nd - 1 - i] = c;
  }
  int decpt = nd + e; /* value = 0.d1 d2 ... x 10^decpt */
  int n = 0;
  if (sign) out[n++] = '-';
  if (decpt > -4 && decpt <= 16) {
    if (decpt <= 0) {
      out[n++] = '0';
      out[n++] = '.';
      for (int i = 0; i < -decpt; i++) out[n++] = '0';
      for (int i = 0; i < nd; i++) out[n++] = dig[i];
    } else if (decpt >= nd) {
      for (int i = 0; i < nd; i++) out[n++] = dig[i];
      for (int i = nd; i < decpt; i++) out[n++] = '0';
      out[n++] = '.';
      out[n++] = '0';
    } else {
      for (int i = 0; i < decpt; i++) out[n++] = dig[i];
      out[n++] = '.';
      for (int i = decpt; i < nd; i++) out[n++] = dig[i];
    }
    return n;
  }
  out[n++] = dig[0];
  if (nd > 1) {
    out[n++] = '.';
    for (int i = 1; i < nd; i++) out[n++] = dig[i];
  }
  int x = decpt - 1;
  out[n++] = 'e';
  out[n++] = x < 0 ? '-' : '+';
  if (x < 0) x = -x;
  if (x >= 100) out[n++] = (char)('0' + x / 100);
  out[n++] = (char)('0' + x / 10 % 10);
  out[n++] = (char)('0' + x % 10);
  return n;
}

int ps_format_double(double f, char* out) {
  int n = format_double(f, out);
  out[n] = '\0';
  return n;
}

int ps_write_csv(const char* path, const char* mode, const char* header, const double* data,
                 long nrows, int ncols) {
  FILE* fh = fopen(path, mode);
  if (!fh) return errno ? errno : EIO;
  /* a row is at most ncols * 26 characters: flush before one might not fit */
  long row_max = (long)ncols * 26 + 2;
  long size = row_max > CSV_BUFFER / 2 ? 2 * row_max : CSV_BUFFER;
  char* buf = malloc((size_t)size);
  if (!buf) {
    fclose(fh);
    return ENOMEM;
  }
  int err = 0;
  long used = 0;
  if (fputs(header, fh) < 0) err = errno ? errno : EIO;
  for (long r = 0; r < nrows && !err; r++) {
    if (used + row_max > size) {
      if (fwrite(buf, 1, (size_t)used, fh) != (size_t)used) err = errno ? errno : EIO;
      used = 0;
    }
    const double* row = data + r * ncols;
    for (int c = 0; c < ncols; c++) {
      if (c) buf[used++] = ',';
      used += format_double(row[c], buf + used);
    }
    buf[used++] = '\r';
    buf[used++] = '\n';
  }
  if (!err && used && fwrite(buf, 1, (size_t)used, fh) != (size_t)used) err = errno ? errno : EIO;
  free(buf);
  if (fclose(fh) != 0 && !err) err = errno ? errno : EIO;
  return err;
}

struct psStream {
  FILE* fh;
  const int* cols; /* (ncols) request channels written after the time */
  int ncols;
};

psStream* ps_stream_open(const char* path, const char* header, const int* cols, int ncols,
                         int* err) {
  psStream* st = calloc(1, sizeof(*st));
  *err = 0;
  if (!st) {
    *err = ENOMEM;
    return NULL;
  }
  st->fh = fopen(path, "w");
  if (!st->fh || fputs(header, st->fh) < 0 || fflush(st->fh) != 0) {
    *err = errno ? errno : EIO;
    if (st->fh) fclose(st->fh);
    free(st);
    return NULL;
  }
  st->cols = cols;
  st->ncols = ncols;
  return st;
}

int ps_stream_rows(psStream* st, const double* t, const double* req, long nrows, int nout,
                   int flush) {
  if (!st) return 0;
  char buf[64];
  for (long r = 0; r < nrows; r++) {
    buf[format_double(t[r], buf)] = '\0';
    if (fputs(buf, st->fh) < 0) return errno ? errno : EIO;
    for (int c = 0; c < st->ncols; c++) {
      buf[0] = ',';
      buf[1 + format_double(req[r * nout + st->cols[c]], buf + 1)] = '\0';
      if (fputs(buf, st->fh) < 0) return errno ? errno : EIO;
    }
    if (fputs("\r\n", st->fh) < 0) return errno ? errno : EIO;
  }
  return flush ? ps_stream_flush(st) : 0;
}

int ps_stream_flush(psStream* st) {
  if (!st) return 0;
  return fflush(st->fh) == 0 ? 0 : (errno ? errno : EIO);
}

void ps_stream_close(psStream* st) {
  if (!st) return;
  fclose(st->fh);
  free(st);
}
