/*
 * bezjoin._native: the optional compiled fast path of the FreeCAD conversions
 * (issue 19, item 7). Built by bindings/python/build-native.sh against the
 * headers of the Python FreeCAD runs; the package works without it (the
 * ctypes route, bezjoin/_freecad.py, gives the same poles bit for bit).
 *
 * It does not link libbezjoin: bezjoin/_freecad.py hands it, through bind(),
 * the addresses of the C functions of the library the ctypes route loaded
 * (one library, one bzj_last_error), FreeCAD's Part.Edge and Part.BezierCurve
 * types, and the verbatim-path bounds of _freecad.py, so both routes decide
 * the same way. Every function returns None where the ctypes route would
 * leave its fast path (another kind of edge, a value it does not take, a
 * library error); the caller then takes the general path, which words the
 * error.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "bezjoin.h"

/* OpenCASCADE's Geom_BezierCurve::MaxDegree() (MAXIMUM_FREECAD_DEGREE). */
#define MAX_DEGREE 25
#define MAX_VALUES (3 * (MAX_DEGREE + 1))
/* bzj_connect_points refuses degrees above 31: orders summing to >= 64 never
 * reach the library on either route. */
#define MAX_ORDER_SUM 64

typedef BzjStatus (*curve_new_fn)(size_t, size_t, const double *, size_t, BzjCurve **);
typedef void (*curve_free_fn)(BzjCurve *);
typedef BzjStatus (*curve_points_fn)(const BzjCurve *, double *, size_t);
typedef BzjStatus (*connect_points_fn)(size_t, const double *, size_t, double, const double *,
                                       size_t, double, size_t, size_t, double, double,
                                       double *, size_t);
typedef BzjStatus (*connect_points_auto_fn)(size_t, const double *, size_t, double,
                                            const double *, size_t, double, size_t, size_t,
                                            double *, size_t, double *);

static curve_new_fn curve_new;
static curve_free_fn curve_free;
static curve_points_fn curve_points;
static connect_points_fn connect_points;
static connect_points_auto_fn connect_points_auto;
static PyObject *edge_type;   /* Part.Edge */
static PyObject *bezier_type; /* Part.BezierCurve */
static PyObject *pointer_type; /* bezjoin._library.CurvePointer */
static double ratios[MAX_DEGREE + 1];
static double reach_limit;

/* The descriptors behind Part.Edge's Degenerated, Curve and ParameterRange
 * (getset descriptors) and Part.BezierCurve's isRational, getPoles and
 * setPoles (method descriptors), found at bind(); NULL when FreeCAD has no
 * such descriptor (then the attribute is asked by name). Calling them skips
 * FreeCAD's __getattro__ (a walk through its method tables and a new bound
 * method per call) and runs the same generated callback (its validity check
 * and C++ exception guard included). They are used for objects of exactly
 * these types only; FreeCAD's __getattro__ also links a returned object to
 * its parent for write-back, which a read of these values does not need. */
static PyObject *d_degenerated, *d_curve, *d_parameter_range, *d_is_rational, *d_get_poles,
    *d_set_poles;

static PyObject *s_degenerated, *s_curve, *s_parameter_range, *s_is_rational, *s_get_poles,
    *s_set_poles, *s_handle, *s_bezier_shape, *s_new;

static int bound(void) {
    if (curve_new && edge_type) {
        return 1;
    }
    PyErr_SetString(PyExc_RuntimeError, "bezjoin._native: bind() was not called");
    return 0;
}

static void *address(PyObject *value) {
    return PyLong_AsVoidPtr(value);
}

/* The descriptor `name` of `type` when it is of the descriptor type `kind`, else NULL
 * (a new reference). */
static PyObject *descriptor(PyObject *type, PyObject *name, PyTypeObject *kind) {
    PyObject *found = _PyType_Lookup((PyTypeObject *)type, name);
    if (!found || !Py_IS_TYPE(found, kind)) {
        return NULL;
    }
    Py_INCREF(found);
    return found;
}

/* obj.<name> for a Part.Edge (through the getset descriptor when obj is exactly one). */
static PyObject *edge_attribute(PyObject *obj, PyObject *descr, PyObject *name) {
    if (descr && Py_TYPE(obj) == (PyTypeObject *)edge_type) {
        return Py_TYPE(descr)->tp_descr_get(descr, obj, (PyObject *)Py_TYPE(obj));
    }
    return PyObject_GetAttr(obj, name);
}

/* curve.<name>(*args) for a Part.BezierCurve (through the method descriptor when
 * curve is exactly one). */
static PyObject *bezier_method(PyObject *curve, PyObject *descr, PyObject *name, PyObject *arg) {
    if (descr && Py_TYPE(curve) == (PyTypeObject *)bezier_type) {
        PyObject *args[2] = {curve, arg};
        return PyObject_Vectorcall(descr, args, arg ? 2 : 1, NULL);
    }
    return arg ? PyObject_CallMethodOneArg(curve, name, arg)
               : PyObject_CallMethodNoArgs(curve, name);
}

static PyObject *bind(PyObject *self, PyObject *args) {
    PyObject *a_new, *a_free, *a_points, *a_connect, *a_auto, *pointer, *edge, *bezier,
        *ratio_seq;
    double limit;
    (void)self;
    if (!PyArg_ParseTuple(args, "OOOOOOOOOd", &a_new, &a_free, &a_points, &a_connect, &a_auto,
                          &pointer, &edge, &bezier, &ratio_seq, &limit)) {
        return NULL;
    }
    if (!PyType_Check(pointer) || !PyType_Check(edge) || !PyType_Check(bezier)) {
        PyErr_SetString(PyExc_TypeError,
                        "bind: CurvePointer, Part.Edge and Part.BezierCurve must be types");
        return NULL;
    }
    PyObject *fast = PySequence_Fast(ratio_seq, "bind: ratios must be a sequence");
    if (!fast) {
        return NULL;
    }
    if (PySequence_Fast_GET_SIZE(fast) != MAX_DEGREE + 1) {
        Py_DECREF(fast);
        PyErr_SetString(PyExc_ValueError, "bind: one ratio per degree 0..25");
        return NULL;
    }
    double new_ratios[MAX_DEGREE + 1];
    for (Py_ssize_t i = 0; i <= MAX_DEGREE; i++) {
        new_ratios[i] = PyFloat_AsDouble(PySequence_Fast_GET_ITEM(fast, i));
        if (new_ratios[i] == -1.0 && PyErr_Occurred()) {
            Py_DECREF(fast);
            return NULL;
        }
    }
    Py_DECREF(fast);
    void *p_new = address(a_new), *p_free = address(a_free), *p_points = address(a_points),
         *p_connect = address(a_connect), *p_auto = address(a_auto);
    if (PyErr_Occurred()) {
        return NULL;
    }
    if (!p_new || !p_free || !p_points || !p_connect || !p_auto) {
        PyErr_SetString(PyExc_ValueError, "bind: a function address is 0");
        return NULL;
    }
    curve_new = (curve_new_fn)p_new;
    curve_free = (curve_free_fn)p_free;
    curve_points = (curve_points_fn)p_points;
    connect_points = (connect_points_fn)p_connect;
    connect_points_auto = (connect_points_auto_fn)p_auto;
    Py_INCREF(pointer);
    Py_XSETREF(pointer_type, pointer);
    Py_INCREF(edge);
    Py_XSETREF(edge_type, edge);
    Py_INCREF(bezier);
    Py_XSETREF(bezier_type, bezier);
    Py_XSETREF(d_degenerated, descriptor(edge, s_degenerated, &PyGetSetDescr_Type));
    Py_XSETREF(d_curve, descriptor(edge, s_curve, &PyGetSetDescr_Type));
    Py_XSETREF(d_parameter_range, descriptor(edge, s_parameter_range, &PyGetSetDescr_Type));
    Py_XSETREF(d_is_rational, descriptor(bezier, s_is_rational, &PyMethodDescr_Type));
    Py_XSETREF(d_get_poles, descriptor(bezier, s_get_poles, &PyMethodDescr_Type));
    Py_XSETREF(d_set_poles, descriptor(bezier, s_set_poles, &PyMethodDescr_Type));
    memcpy(ratios, new_ratios, sizeof ratios);
    reach_limit = limit;
    Py_RETURN_NONE;
}

/* Python's max(a, b, ...) on floats: keeps the first unless a later one
 * compares greater (a NaN first stays; a NaN later is skipped). */
static double python_max(double current, double next) {
    return next > current ? next : current;
}

/* _freecad._verbatim_values: 1 and the poles' coordinates in values[0..*length)
 * when the edge takes the fast path, 0 when it does not (no exception set),
 * -1 on an exception that the ctypes route raises too. */
static int verbatim_values(PyObject *obj, double *values, size_t *length, size_t *degree_out) {
    int is_edge = PyObject_IsInstance(obj, edge_type);
    if (is_edge <= 0) {
        return is_edge;
    }
    PyObject *degenerated = edge_attribute(obj, d_degenerated, s_degenerated);
    if (!degenerated) {
        return -1; /* raised outside the try in _verbatim_values too */
    }
    int is_degenerated = PyObject_IsTrue(degenerated);
    Py_DECREF(degenerated);
    if (is_degenerated) {
        return is_degenerated < 0 ? -1 : 0;
    }
    /* try: curve = obj.Curve; whole = obj.ParameterRange == (0.0, 1.0)
     * except Exception: return None */
    PyObject *curve = edge_attribute(obj, d_curve, s_curve);
    if (!curve) {
        goto swallow;
    }
    PyObject *range = edge_attribute(obj, d_parameter_range, s_parameter_range);
    if (!range) {
        Py_DECREF(curve);
        goto swallow;
    }
    int whole = 0;
    if (PyTuple_CheckExact(range) && PyTuple_GET_SIZE(range) == 2 &&
        PyFloat_CheckExact(PyTuple_GET_ITEM(range, 0)) &&
        PyFloat_CheckExact(PyTuple_GET_ITEM(range, 1))) {
        whole = PyFloat_AS_DOUBLE(PyTuple_GET_ITEM(range, 0)) == 0.0 &&
                PyFloat_AS_DOUBLE(PyTuple_GET_ITEM(range, 1)) == 1.0;
    } else {
        /* Not FreeCAD's tuple of two floats: compare as Python does. */
        PyObject *reference = Py_BuildValue("(dd)", 0.0, 1.0);
        whole = reference ? PyObject_RichCompareBool(range, reference, Py_EQ) : -1;
        Py_XDECREF(reference);
    }
    Py_DECREF(range);
    if (whole < 0) {
        Py_DECREF(curve);
        goto swallow;
    }
    if (!whole || (PyObject *)Py_TYPE(curve) != bezier_type) {
        Py_DECREF(curve);
        return 0;
    }
    PyObject *rational = bezier_method(curve, d_is_rational, s_is_rational, NULL);
    if (!rational) {
        Py_DECREF(curve);
        return -1;
    }
    int is_rational = PyObject_IsTrue(rational);
    Py_DECREF(rational);
    if (is_rational) {
        Py_DECREF(curve);
        return is_rational < 0 ? -1 : 0;
    }
    PyObject *poles = bezier_method(curve, d_get_poles, s_get_poles, NULL);
    Py_DECREF(curve);
    if (!poles) {
        return -1;
    }
    PyObject *list = PySequence_Fast(poles, "getPoles() did not return a sequence");
    Py_DECREF(poles);
    if (!list) {
        return -1;
    }
    Py_ssize_t count = PySequence_Fast_GET_SIZE(list);
    if (count < 2 || count > MAX_DEGREE + 1) {
        Py_DECREF(list);
        return 0;
    }
    size_t n = 0;
    for (Py_ssize_t i = 0; i < count; i++) {
        PyObject *pole = PySequence_Fast_GET_ITEM(list, i);
        /* FreeCAD's Vector is a sequence of its three floats (as _chain reads it). */
        if (!PySequence_Check(pole) || PySequence_Size(pole) != 3) {
            PyErr_Clear();
            Py_DECREF(list);
            return 0;
        }
        for (Py_ssize_t k = 0; k < 3; k++) {
            PyObject *item = PySequence_GetItem(pole, k);
            if (!item) {
                Py_DECREF(list);
                return -1;
            }
            if (!PyFloat_CheckExact(item)) {
                Py_DECREF(item);
                Py_DECREF(list);
                return 0;
            }
            values[n++] = PyFloat_AS_DOUBLE(item);
            Py_DECREF(item);
        }
    }
    Py_DECREF(list);
    size_t degree = (size_t)count - 1;
    double reach = fabs(values[0]);
    for (size_t i = 1; i < n; i++) {
        reach = python_max(reach, fabs(values[i]));
    }
    double ratio = ratios[degree];
    if (!(reach <= ratio)) {
        if (!(reach < reach_limit)) {
            return 0;
        }
        double ends = 1.0;
        ends = python_max(ends, fabs(values[0]));
        ends = python_max(ends, fabs(values[1]));
        ends = python_max(ends, fabs(values[2]));
        ends = python_max(ends, fabs(values[n - 3]));
        ends = python_max(ends, fabs(values[n - 2]));
        ends = python_max(ends, fabs(values[n - 1]));
        if (!(reach <= ratio * ends)) {
            return 0;
        }
    }
    *length = n;
    *degree_out = degree;
    return 1;
swallow:
    if (PyErr_ExceptionMatches(PyExc_Exception)) {
        PyErr_Clear();
        return 0;
    }
    return -1;
}

/* A new Part.BezierCurve with the 3D poles values[0..3 count): Part.BezierCurve()
 * and one setPoles of 3-tuples (as _freecad.bezier_curve_from_values). */
static PyObject *bezier_from_values(const double *values, size_t count) {
    PyObject *rows = PyList_New((Py_ssize_t)count);
    if (!rows) {
        return NULL;
    }
    for (size_t i = 0; i < count; i++) {
        PyObject *row = Py_BuildValue("(ddd)", values[3 * i], values[3 * i + 1],
                                      values[3 * i + 2]);
        if (!row) {
            Py_DECREF(rows);
            return NULL;
        }
        PyList_SET_ITEM(rows, (Py_ssize_t)i, row);
    }
    PyObject *curve = PyObject_CallNoArgs(bezier_type);
    if (!curve) {
        Py_DECREF(rows);
        return NULL;
    }
    PyObject *done = bezier_method(curve, d_set_poles, s_set_poles, rows);
    Py_DECREF(rows);
    if (!done) {
        Py_DECREF(curve);
        return NULL;
    }
    Py_DECREF(done);
    return curve;
}

static int handle_buffer(PyObject *handle, Py_buffer *view, int writable) {
    if (PyObject_GetBuffer(handle, view, writable ? PyBUF_WRITABLE : PyBUF_SIMPLE) < 0) {
        return 0;
    }
    if (view->len != (Py_ssize_t)sizeof(void *)) {
        PyBuffer_Release(view);
        PyErr_SetString(PyExc_TypeError, "expected a ctypes pointer (a CurvePointer)");
        return 0;
    }
    return 1;
}

/* A new instance of the class `cls` without __init__ (cls.__new__(cls)). */
static PyObject *bare_instance(PyObject *cls) {
    PyTypeObject *type = (PyTypeObject *)cls;
    if (type->tp_new == PyBaseObject_Type.tp_new) {
        PyObject *empty = PyTuple_New(0);
        if (!empty) {
            return NULL;
        }
        PyObject *instance = type->tp_new(type, empty, NULL);
        Py_DECREF(empty);
        return instance;
    }
    return PyObject_CallMethodOneArg(cls, s_new, cls);
}

/* The Curve (class `cls`) owning `curve`, a Bezier curve of this degree in 3D:
 * as Curve._adopt(handle, (degree, 3)). Frees `curve` on a failure. */
static PyObject *adopt(PyObject *cls, BzjCurve *curve, size_t degree) {
    PyObject *handle = PyObject_CallNoArgs(pointer_type);
    if (!handle) {
        curve_free(curve);
        return NULL;
    }
    Py_buffer view;
    if (PyObject_GetBuffer(handle, &view, PyBUF_WRITABLE) < 0 ||
        view.len != (Py_ssize_t)sizeof curve) {
        if (!PyErr_Occurred()) {
            PyBuffer_Release(&view);
            PyErr_SetString(PyExc_TypeError, "CurvePointer is not a pointer");
        }
        Py_DECREF(handle);
        curve_free(curve);
        return NULL;
    }
    memcpy(view.buf, &curve, sizeof curve);
    PyBuffer_Release(&view);
    PyObject *shape = Py_BuildValue("(ni)", (Py_ssize_t)degree, 3);
    PyObject *instance = shape ? bare_instance(cls) : NULL;
    if (!instance || PyObject_SetAttr(instance, s_handle, handle) < 0) {
        /* No Curve owns the curve. */
        curve_free(curve);
        Py_XDECREF(instance);
        Py_XDECREF(shape);
        Py_DECREF(handle);
        return NULL;
    }
    Py_DECREF(handle);
    /* From here the instance owns the curve (its close() frees it). */
    int failed = PyObject_SetAttr(instance, s_bezier_shape, shape) < 0;
    Py_DECREF(shape);
    if (failed) {
        Py_DECREF(instance);
        return NULL;
    }
    return instance;
}

/* curve_new(obj, cls): the fast path of Curve.from_freecad. When obj is an
 * edge on the whole of a polynomial Part.BezierCurve that the verbatim path
 * takes, the Bezier curve with its poles (bzj_curve_new) as an instance of
 * cls (a Curve, as Curve._adopt makes it); else None. */
static PyObject *native_curve_new(PyObject *self, PyObject *const *args, Py_ssize_t nargs) {
    (void)self;
    if (nargs != 2) {
        PyErr_SetString(PyExc_TypeError, "curve_new takes 2 arguments");
        return NULL;
    }
    if (!bound()) {
        return NULL;
    }
    if (!PyType_Check(args[1])) {
        PyErr_SetString(PyExc_TypeError, "curve_new: cls must be a class");
        return NULL;
    }
    double values[MAX_VALUES];
    size_t length = 0, degree = 0;
    int found = verbatim_values(args[0], values, &length, &degree);
    if (found <= 0) {
        if (found < 0) {
            return NULL;
        }
        Py_RETURN_NONE;
    }
    BzjCurve *out = NULL;
    BzjStatus status = curve_new(3, degree, values, length, &out);
    if (status != BZJ_OK || !out) {
        Py_RETURN_NONE;
    }
    return adopt(args[1], out, degree);
}

/* curve_free(handle): bzj_curve_free of the CurvePointer's curve (Curve.close). */
static PyObject *native_curve_free(PyObject *self, PyObject *handle) {
    (void)self;
    if (!bound()) {
        return NULL;
    }
    Py_buffer view;
    if (!handle_buffer(handle, &view, 0)) {
        return NULL;
    }
    BzjCurve *curve;
    memcpy(&curve, view.buf, sizeof curve);
    PyBuffer_Release(&view);
    if (curve) {
        curve_free(curve);
    }
    Py_RETURN_NONE;
}

/* bezier_curve(handle, degree): the Part.BezierCurve of the 3D Bezier curve
 * of this degree (the caller knows it) behind the CurvePointer `handle`
 * (bzj_curve_points), or None on a library error (the caller then asks
 * through ctypes, which raises the library's message). */
static PyObject *native_bezier_curve(PyObject *self, PyObject *args) {
    PyObject *handle;
    Py_ssize_t degree;
    (void)self;
    if (!PyArg_ParseTuple(args, "On", &handle, &degree) || !bound()) {
        return NULL;
    }
    if (degree < 1 || degree > MAX_DEGREE) {
        Py_RETURN_NONE;
    }
    Py_buffer view;
    if (!handle_buffer(handle, &view, 0)) {
        return NULL;
    }
    const BzjCurve *curve;
    memcpy(&curve, view.buf, sizeof curve);
    PyBuffer_Release(&view);
    if (!curve) {
        Py_RETURN_NONE;
    }
    double values[MAX_VALUES];
    size_t count = (size_t)degree + 1;
    if (curve_points(curve, values, 3 * count) != BZJ_OK) {
        Py_RETURN_NONE;
    }
    return bezier_from_values(values, count);
}

/* An order: None (the degree) or an exact non-negative int; 0 otherwise
 * (the Python route validates it). */
static int order_argument(PyObject *value, size_t degree, size_t *out) {
    if (value == Py_None) {
        *out = degree;
        return 1;
    }
    if (!PyLong_CheckExact(value)) {
        return 0;
    }
    size_t order = PyLong_AsSize_t(value);
    if (order == (size_t)-1 && PyErr_Occurred()) {
        PyErr_Clear();
        return 0;
    }
    *out = order;
    return 1;
}

/* A real: an exact float or int (real_argument's float(value)); 0 otherwise. */
static int real_value(PyObject *value, double *out) {
    if (PyFloat_CheckExact(value)) {
        *out = PyFloat_AS_DOUBLE(value);
        return 1;
    }
    if (PyLong_CheckExact(value)) {
        double x = PyLong_AsDouble(value);
        if (x == -1.0 && PyErr_Occurred()) {
            PyErr_Clear();
            return 0;
        }
        *out = x;
        return 1;
    }
    return 0;
}

/* connect_edges(p_edge, u0, q_edge, v0, p_order, q_order, p_scale, q_scale,
 * auto_scale): the fast path of bezjoin.connect_edges (same arguments, same
 * scale rule as automatic_scale); the blend as a Part.BezierCurve; None when
 * the edges are not both on the verbatim path (the caller composes
 * from_freecad, connect and to_freecad, as the ctypes route does);
 * NotImplemented for anything else (an argument of another type, an order
 * out of range, a library error): the caller then runs the ctypes route,
 * which validates, words the error or composes. */
static PyObject *native_connect_edges(PyObject *self, PyObject *const *args, Py_ssize_t nargs) {
    (void)self;
    if (nargs != 9) {
        PyErr_SetString(PyExc_TypeError, "connect_edges takes 9 arguments");
        return NULL;
    }
    if (!bound()) {
        return NULL;
    }
    PyObject *p_edge = args[0], *q_edge = args[2], *auto_scale = args[8];
    double u0, v0, p_scale = 1.0, q_scale = 1.0;
    int automatic;
    if (auto_scale == Py_None) {
        automatic = args[6] == Py_None && args[7] == Py_None;
    } else if (auto_scale == Py_True || auto_scale == Py_False) {
        automatic = auto_scale == Py_True;
    } else {
        Py_RETURN_NOTIMPLEMENTED;
    }
    if (!real_value(args[1], &u0) || !real_value(args[3], &v0) ||
        (args[6] != Py_None && !real_value(args[6], &p_scale)) ||
        (args[7] != Py_None && !real_value(args[7], &q_scale))) {
        Py_RETURN_NOTIMPLEMENTED;
    }
    double p_values[MAX_VALUES], q_values[MAX_VALUES];
    size_t p_length, q_length, p_degree, q_degree;
    int found = verbatim_values(p_edge, p_values, &p_length, &p_degree);
    if (found > 0) {
        found = verbatim_values(q_edge, q_values, &q_length, &q_degree);
    }
    if (found <= 0) {
        if (found < 0) {
            return NULL;
        }
        Py_RETURN_NONE;
    }
    size_t p_order, q_order;
    if (!order_argument(args[4], p_degree, &p_order) ||
        !order_argument(args[5], q_degree, &q_order)) {
        Py_RETURN_NOTIMPLEMENTED;
    }
    /* A degree above MAX_DEGREE cannot be a Part.BezierCurve: the general path
     * raises (as bezier_curve_from_values would), the library is not asked here. */
    if (p_order >= MAX_ORDER_SUM || q_order >= MAX_ORDER_SUM ||
        p_order + q_order + 1 > MAX_DEGREE) {
        Py_RETURN_NOTIMPLEMENTED;
    }
    size_t count = p_order + q_order + 2;
    double out[MAX_VALUES];
    BzjStatus status;
    if (automatic) {
        double scale;
        status = connect_points_auto(3, p_values, p_length, u0, q_values, q_length, v0,
                                     p_order, q_order, out, 3 * count, &scale);
    } else {
        status = connect_points(3, p_values, p_length, u0, q_values, q_length, v0, p_order,
                                q_order, p_scale, q_scale, out, 3 * count);
    }
    if (status != BZJ_OK) {
        Py_RETURN_NOTIMPLEMENTED;
    }
    return bezier_from_values(out, count);
}

static PyMethodDef methods[] = {
    {"bind", bind, METH_VARARGS,
     "bind(curve_new, curve_free, curve_points, connect_points, connect_points_auto_scale, "
     "CurvePointer, Part.Edge, Part.BezierCurve, ratios, limit): the library functions "
     "(addresses) and FreeCAD types to use."},
    {"curve_new", (PyCFunction)(void (*)(void))native_curve_new, METH_FASTCALL,
     "curve_new(edge, cls) -> cls instance or None: the fast path of Curve.from_freecad."},
    {"curve_free", native_curve_free, METH_O,
     "curve_free(handle): bzj_curve_free of a CurvePointer's curve."},
    {"bezier_curve", native_bezier_curve, METH_VARARGS,
     "bezier_curve(handle, degree) -> Part.BezierCurve or None: a 3D Bezier curve out."},
    {"connect_edges", (PyCFunction)(void (*)(void))native_connect_edges, METH_FASTCALL,
     "connect_edges(p_edge, u0, q_edge, v0, p_order, q_order, p_scale, q_scale, auto_scale)"
     " -> Part.BezierCurve, None or NotImplemented: the fast path of bezjoin.connect_edges."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "bezjoin._native",
    "The optional compiled fast path of bezjoin's FreeCAD conversions.", -1, methods,
    NULL, NULL, NULL, NULL,
};

PyMODINIT_FUNC PyInit__native(void) {
    s_degenerated = PyUnicode_InternFromString("Degenerated");
    s_curve = PyUnicode_InternFromString("Curve");
    s_parameter_range = PyUnicode_InternFromString("ParameterRange");
    s_is_rational = PyUnicode_InternFromString("isRational");
    s_get_poles = PyUnicode_InternFromString("getPoles");
    s_set_poles = PyUnicode_InternFromString("setPoles");
    s_handle = PyUnicode_InternFromString("_handle");
    s_bezier_shape = PyUnicode_InternFromString("_bezier_shape");
    s_new = PyUnicode_InternFromString("__new__");
    if (!s_degenerated || !s_curve || !s_parameter_range || !s_is_rational || !s_get_poles ||
        !s_set_poles || !s_handle || !s_bezier_shape || !s_new) {
        return NULL;
    }
    return PyModule_Create(&module);
}
