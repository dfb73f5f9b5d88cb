//
// Copyright (c) 2024 ZettaScale Technology
//
// This program and the accompanying materials are made available under the
// terms of the Eclipse Public License 2.0 which is available at
// http://www.eclipse.org/legal/epl-2.0, or the Apache License, Version 2.0
// which is available at https://www.apache.org/licenses/LICENSE-2.0.
//
// SPDX-License-Identifier: EPL-2.0 OR Apache-2.0
//
// Contributors:
//   ZettaScale Zenoh Team, <zenoh@zettascale.tech>
//

#include "zenoh-pico/collections/bytes.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "zenoh-pico/api/olv_macros.h"
#include "zenoh-pico/protocol/codec/core.h"
#include "zenoh-pico/system/platform.h"
#include "zenoh-pico/utils/endianness.h"
#include "zenoh-pico/utils/result.h"

/*-------- Bytes --------*/
bool _z_bytes_check(const _z_bytes_t *bytes) { return !_z_bytes_is_empty(bytes); }

z_result_t _z_bytes_copy(_z_bytes_t *dst, const _z_bytes_t *src) {
    *dst = _z_bytes_null();
    size_t num_slices = _z_bytes_num_slices(src);
    if (num_slices == 0) {
        return _Z_RES_OK;
    }
    for (size_t i = 0; i < num_slices; ++i) {
        _z_slice_t s = _z_slice_null();
        _Z_CLEAN_RETURN_IF_ERR(_z_slice_copy(&s, _z_bytes_get_slice(src, i)), _z_bytes_clear(dst));
        _Z_CLEAN_RETURN_IF_ERR(_z_bytes_append_slice(dst, &s), _z_bytes_clear(dst));
    }
    return _Z_RES_OK;
}

size_t _z_bytes_len(const _z_bytes_t *bs) {
    size_t len = 0;
    for (size_t i = 0; i < _z_bytes_num_slices(bs); ++i) {
        len += _z_bytes_get_slice(bs, i)->len;
    }
    return len;
}

bool _z_bytes_is_empty(const _z_bytes_t *bs) {
    for (size_t i = 0; i < _z_bytes_num_slices(bs); i++) {
        if (_z_bytes_get_slice(bs, i)->len > 0) return false;
    }
    return true;
}

void _z_bytes_free(_z_bytes_t **bs) {
    _z_bytes_t *ptr = *bs;

    if (ptr != NULL) {
        _z_bytes_clear(ptr);

        z_free(ptr);
        *bs = NULL;
    }
}

size_t _z_bytes_to_buf(const _z_bytes_t *bytes, uint8_t *dst, size_t len) {
    uint8_t *start = dst;
    size_t remaining = len;
    for (size_t i = 0; i < _z_bytes_num_slices(bytes) && remaining > 0; ++i) {
        // Recopy data
        const _z_slice_t *s = _z_bytes_get_slice(bytes, i);
        size_t s_len = s->len;
        size_t len_to_copy = remaining >= s_len ? s_len : remaining;
        // SAFETY: len_to_copy is guaranteed to fit into start buffer by construction.
        // Flawfinder: ignore [CWE-120]
        memcpy(start, s->start, len_to_copy);
        start += len_to_copy;
        remaining -= len_to_copy;
    }

    return len - remaining;
}
z_result_t _z_bytes_from_slice(_z_bytes_t *b, _z_slice_t *s) {
    *b = _z_bytes_null();
    return _z_bytes_append_slice(b, s);
}

z_result_t _z_bytes_copy_from_buf(_z_bytes_t *b, const uint8_t *src, size_t len) {
    *b = _z_bytes_null();
    if (len == 0) return _Z_RES_OK;
    _z_slice_t s = _z_slice_copy_from_buf(src, len);
    if (s.len != len) _Z_ERROR_RETURN(_Z_ERR_SYSTEM_OUT_OF_MEMORY);
    return _z_bytes_from_slice(b, &s);
}

z_result_t _z_bytes_to_slice(const _z_bytes_t *bytes, _z_slice_t *s) {
    // Allocate slice
    size_t len = _z_bytes_len(bytes);
    *s = _z_slice_make(len);
    if (!_z_slice_check(s) && len > 0) {
        _Z_ERROR_RETURN(_Z_ERR_SYSTEM_OUT_OF_MEMORY);
    }
    uint8_t *start = (uint8_t *)s->start;
    for (size_t i = 0; i < _z_bytes_num_slices(bytes); ++i) {
        // Recopy data
        const _z_slice_t *sl = _z_bytes_get_slice(bytes, i);
        size_t s_len = sl->len;
        // SAFETY: s_len is guaranteed to fit into start buffer by construction.
        // Flawfinder: ignore [CWE-120]
        memcpy(start, sl->start, s_len);
        start += s_len;
    }

    return _Z_RES_OK;
}

z_result_t _z_bytes_append_slice(_z_bytes_t *dst, _z_slice_t *s) {
    switch (_z_slice_single_or_vec_tag(&dst->_inner)) {
        case _z_slice_single_or_vec_tag_none: {
            // Empty bytes: store the slice inline (common single-slice case, no allocation).
            dst->_inner = _z_slice_single_or_vec_from_slice(s);
            break;
        }
        case _z_slice_single_or_vec_tag_slice: {
            // Promote from a single inline slice to a vector holding both slices.
            _z_slice_vec_t vec = _z_slice_vec_new();
            if (!_z_slice_vec_reserve(&vec, 2)) {
                _z_slice_clear(s);
                _Z_ERROR_RETURN(_Z_ERR_SYSTEM_OUT_OF_MEMORY);
            }
            _z_slice_t first = _z_slice_null();
            // Move the existing inline slice out of the variant into the vector.
            (void)_z_slice_single_or_vec_take_slice(&dst->_inner, &first);
            _z_slice_vec_push_back(&vec, &first);
            _z_slice_vec_push_back(&vec, s);
            dst->_inner = _z_slice_single_or_vec_from_vec(&vec);
            break;
        }
        case _z_slice_single_or_vec_tag_vec: {
            _z_slice_vec_t *vec = _z_slice_single_or_vec_get_vec(&dst->_inner);
            if (!_z_slice_vec_push_back(vec, s)) {
                _z_slice_clear(s);
                _Z_ERROR_RETURN(_Z_ERR_SYSTEM_OUT_OF_MEMORY);
            }
            break;
        }
    }
    return _Z_RES_OK;
}

z_result_t _z_bytes_append_bytes(_z_bytes_t *dst, _z_bytes_t *src) {
    // Fast path: if `dst` is empty, just move `src` wholesale, preserving its
    // single-slice or vector representation (and avoiding any reallocation).
    if (_z_slice_single_or_vec_is_none(&dst->_inner)) {
        return _z_bytes_move(dst, src);
    }

    z_result_t res = _Z_RES_OK;
    for (size_t i = 0; i < _z_bytes_num_slices(src); ++i) {
        _z_slice_t s = _z_slice_null();
        // Move the slice out of `src` so ownership is transferred to `dst`
        _z_slice_t *src_slice = (_z_slice_t *)_z_bytes_get_slice(src, i);
        s = *src_slice;
        *src_slice = _z_slice_null();
        res = _z_bytes_append_slice(dst, &s);
        if (res != _Z_RES_OK) {
            break;
        }
    }

    _z_bytes_clear(src);
    return res;
}

z_result_t _z_bytes_move(_z_bytes_t *dst, _z_bytes_t *src) {
    *dst = *src;
    *src = _z_bytes_null();
    return _Z_RES_OK;
}

_z_bytes_reader_t _z_bytes_get_reader(const _z_bytes_t *bytes) {
    _z_bytes_reader_t r;
    r.bytes = bytes;
    r.slice_idx = 0;
    r.byte_idx = 0;
    r.in_slice_idx = 0;
    return r;
}

z_result_t _z_bytes_reader_seek_forward(_z_bytes_reader_t *reader, size_t offset) {
    size_t start_slice = reader->slice_idx;
    for (size_t i = start_slice; i < _z_bytes_num_slices(reader->bytes); ++i) {
        const _z_slice_t *s = _z_bytes_get_slice(reader->bytes, i);
        size_t remaining = s->len - reader->in_slice_idx;
        if (offset >= remaining) {
            reader->slice_idx += 1;
            reader->in_slice_idx = 0;
            reader->byte_idx += remaining;
            offset -= remaining;
        } else {
            reader->in_slice_idx += offset;
            reader->byte_idx += offset;
            offset = 0;
        }
        if (offset == 0) break;
    }

    if (offset > 0) _Z_ERROR_RETURN(_Z_ERR_DID_NOT_READ);
    return _Z_RES_OK;
}

z_result_t _z_bytes_reader_seek_backward(_z_bytes_reader_t *reader, size_t offset) {
    while (offset != 0) {
        if (reader->in_slice_idx == 0) {
            if (reader->slice_idx == 0) _Z_ERROR_RETURN(_Z_ERR_DID_NOT_READ);
            reader->slice_idx--;
            const _z_slice_t *s = _z_bytes_get_slice(reader->bytes, reader->slice_idx);
            reader->in_slice_idx = s->len;
        }

        if (offset > reader->in_slice_idx) {
            offset -= reader->in_slice_idx;
            reader->byte_idx -= reader->in_slice_idx;
            reader->in_slice_idx = 0;
        } else {
            reader->byte_idx -= offset;
            reader->in_slice_idx -= offset;
            offset = 0;
        }
    }
    return _Z_RES_OK;
}

z_result_t _z_bytes_reader_seek(_z_bytes_reader_t *reader, int64_t offset, int origin) {
    switch (origin) {
        case SEEK_SET: {
            reader->byte_idx = 0;
            reader->in_slice_idx = 0;
            reader->slice_idx = 0;
            if (offset < 0) _Z_ERROR_RETURN(_Z_ERR_DID_NOT_READ);
            return _z_bytes_reader_seek_forward(reader, (size_t)offset);
        }
        case SEEK_CUR: {
            if (offset >= 0)
                return _z_bytes_reader_seek_forward(reader, (size_t)offset);
            else
                return _z_bytes_reader_seek_backward(reader, (size_t)(-offset));
        }
        case SEEK_END: {
            reader->byte_idx = _z_bytes_len(reader->bytes);
            reader->in_slice_idx = 0;
            reader->slice_idx = _z_bytes_num_slices(reader->bytes);
            if (offset > 0)
                _Z_ERROR_RETURN(_Z_ERR_DID_NOT_READ);
            else
                return _z_bytes_reader_seek_backward(reader, (size_t)(-offset));
        }
        default:
            _Z_ERROR_RETURN(_Z_ERR_GENERIC);
    }
}

int64_t _z_bytes_reader_tell(const _z_bytes_reader_t *reader) { return (int64_t)reader->byte_idx; }

size_t _z_bytes_reader_read(_z_bytes_reader_t *reader, uint8_t *buf, size_t len) {
    uint8_t *buf_start = buf;
    size_t to_read = len;
    for (size_t i = reader->slice_idx; i < _z_bytes_num_slices(reader->bytes); ++i) {
        const _z_slice_t *s = _z_bytes_get_slice(reader->bytes, i);
        size_t remaining = s->len - reader->in_slice_idx;
        if (len >= remaining) {
            // SAFETY: remaining is guaranteed to fit into buf_start buffer by construction.
            // Flawfinder: ignore [CWE-120]
            memcpy(buf_start, s->start + reader->in_slice_idx, remaining);
            reader->slice_idx += 1;
            reader->in_slice_idx = 0;
            reader->byte_idx += remaining;
            len -= remaining;
            buf_start += remaining;
        } else {
            // SAFETY: len is guaranteed to fit into buf_start buffer by construction.
            // Flawfinder: ignore [CWE-120]
            memcpy(buf_start, s->start + reader->in_slice_idx, len);
            reader->in_slice_idx += len;
            reader->byte_idx += len;
            len = 0;
        }
        if (len == 0) break;
    }

    return to_read - len;
}

z_result_t _z_bytes_reader_read_slices(_z_bytes_reader_t *reader, size_t len, _z_bytes_t *out) {
    *out = _z_bytes_null();
    z_result_t res = _Z_RES_OK;

    for (size_t i = reader->slice_idx; i < _z_bytes_num_slices(reader->bytes) && len > 0; ++i) {
        const _z_slice_t *s = _z_bytes_get_slice(reader->bytes, i);
        size_t s_len = s->len;

        size_t remaining = s_len - reader->in_slice_idx;
        size_t len_to_copy = remaining > len ? len : remaining;
        _z_slice_t ss = _z_slice_null();
        res = _z_slice_n_copy(&ss, s, reader->in_slice_idx, len_to_copy);
        reader->in_slice_idx += len_to_copy;
        reader->byte_idx += len_to_copy;
        if (reader->in_slice_idx == s_len) {
            reader->slice_idx++;
            reader->in_slice_idx = 0;
        }

        if (res != _Z_RES_OK) {
            _Z_ERROR_LOG(_Z_ERR_SYSTEM_OUT_OF_MEMORY);
            res = _Z_ERR_SYSTEM_OUT_OF_MEMORY;
            break;
        }

        res = _z_bytes_append_slice(out, &ss);
        if (res != _Z_RES_OK) {
            break;
        }
        len -= len_to_copy;
    }
    if (len > 0 && res == _Z_RES_OK) {
        _Z_ERROR_LOG(_Z_ERR_DID_NOT_READ);
        res = _Z_ERR_DID_NOT_READ;
    }
    if (res != _Z_RES_OK) {
        _z_bytes_clear(out);
        _Z_ERROR_RETURN(res);
    }
    return _Z_RES_OK;
}

_z_bytes_writer_t _z_bytes_writer_from_bytes(_z_bytes_t *bytes) {
    _z_bytes_writer_t writer;
    writer.cache = (_z_write_buf_t){0};
    writer.bytes = _z_bytes_steal(bytes);
    return writer;
}

_z_bytes_writer_t _z_bytes_writer_empty(void) {
    _z_bytes_writer_t writer;
    writer.cache = (_z_write_buf_t){0};
    writer.bytes = _z_bytes_null();
    return writer;
}

bool _z_bytes_writer_is_empty(const _z_bytes_writer_t *writer) {
    return _z_bytes_is_empty(&writer->bytes) && _z_uint8_vec_is_empty(&writer->cache._buffer);
}

bool _z_bytes_writer_check(const _z_bytes_writer_t *writer) { return !_z_bytes_writer_is_empty(writer); }

// Flushes the contiguous write cache into `bytes` as a single owned slice.
// The cache buffer's ownership is transferred to the slice and the cache is
// reinitialized empty (without freeing the moved-out buffer). No-op if empty.
static z_result_t _z_bytes_writer_flush_cache(_z_bytes_writer_t *writer) {
    if (_z_uint8_vec_is_empty(&writer->cache._buffer)) {
        return _Z_RES_OK;
    }
    _z_slice_t s = _z_write_buf_into_slice(&writer->cache);
    _Z_CLEAN_RETURN_IF_ERR(_z_bytes_append_slice(&writer->bytes, &s), _z_slice_clear(&s));
    return _Z_RES_OK;
}

z_result_t _z_bytes_writer_write_all(_z_bytes_writer_t *writer, const uint8_t *src, size_t len) {
    if (len == 0) {
        return _Z_RES_OK;
    }
    return _z_write_buf_write_bytes(&writer->cache, src, len);
}

z_result_t _z_bytes_writer_append_z_bytes(_z_bytes_writer_t *writer, _z_bytes_t *src) {
    _Z_CLEAN_RETURN_IF_ERR(_z_bytes_writer_flush_cache(writer), _z_bytes_clear(src));
    _Z_CLEAN_RETURN_IF_ERR(_z_bytes_append_bytes(&writer->bytes, src), _z_bytes_clear(src));
    return _Z_RES_OK;
}

z_result_t _z_bytes_writer_append_slice(_z_bytes_writer_t *writer, _z_slice_t *src) {
    _Z_CLEAN_RETURN_IF_ERR(_z_bytes_writer_flush_cache(writer), _z_slice_clear(src));
    _Z_CLEAN_RETURN_IF_ERR(_z_bytes_append_slice(&writer->bytes, src), _z_slice_clear(src));
    return _Z_RES_OK;
}

_z_bytes_t _z_bytes_writer_finish(_z_bytes_writer_t *writer) {
    _z_bytes_t out = _z_bytes_null();
    if (_z_bytes_writer_flush_cache(writer) != _Z_RES_OK) {
        _z_bytes_writer_clear(writer);
        return out;
    }
    _z_bytes_move(&out, &writer->bytes);
    return out;
}

void _z_bytes_writer_clear(_z_bytes_writer_t *writer) {
    _z_write_buf_destroy(&writer->cache);
    _z_bytes_clear(&writer->bytes);
}

z_result_t _z_bytes_writer_move(_z_bytes_writer_t *dst, _z_bytes_writer_t *src) {
    dst->cache = src->cache;
    _z_bytes_move(&dst->bytes, &src->bytes);
    src->cache = (_z_write_buf_t){0};
    return _Z_RES_OK;
}

size_t _z_bytes_reader_remaining(const _z_bytes_reader_t *reader) {
    return _z_bytes_len(reader->bytes) - reader->byte_idx;
}
